// Outgoing frames: a writer that streams one frame through the transport in
// small pieces, and the messages a node sends besides its description
// (protocol.md §5). Every length is computed before the header is written,
// so a frame never needs to exist whole in memory.

#include "node_internal.h"

#include <stddef.h>

#define BYTE_MASK 0xFF
#define BYTE_BITS 8
// A UTF-8 continuation byte is 10xxxxxx.
#define UTF8_CONTINUATION_MASK  0xC0
#define UTF8_CONTINUATION_VALUE 0x80

// The header goes into the transmit buffer at once, before any piece leaves.
typedef char header_fits_a_piece[NODE_TRANSMIT_CHUNK > NODE_HEADER_SIZE ? 1 : -1];

static void store_u16(uint8_t *bytes, uint16_t value)
{
    bytes[0] = (uint8_t)(value & BYTE_MASK);
    bytes[1] = (uint8_t)(value >> BYTE_BITS);
}

static void flush(node_state *node, bool frame_complete)
{
    node->transport.send(
      node->transport.context, node->transmit, node->transmit_fill, frame_complete);
    node->transmit_fill = 0;
}

void node_frame_put_byte(node_state *node, uint8_t byte)
{
    if (node->transmit_left == 0)
        return; // more than announced: never let it reach the wire
    node->transmit[node->transmit_fill++] = byte;
    node->transmit_left--;
    // The last piece is sent by node_frame_end, marked as such.
    if (node->transmit_fill == NODE_TRANSMIT_CHUNK && node->transmit_left > 0)
        flush(node, false);
}

void node_frame_begin(node_state *node, uint16_t type, uint16_t payload_length)
{
    if (payload_length > NODE_MAX_PAYLOAD)
        payload_length = NODE_MAX_PAYLOAD;
    // Every message starts a frame: its header is stored directly, not a
    // byte at a time through the checks of node_frame_put_byte.
    store_u16(node->transmit + 2 * FRAME_LENGTH, payload_length);
    store_u16(node->transmit + 2 * FRAME_SOURCE, node->vm.node_id);
    store_u16(node->transmit + 2 * FRAME_TYPE, type);
    node->transmit_fill = NODE_HEADER_SIZE;
    node->transmit_left = payload_length;
}

void node_frame_put_u16(node_state *node, uint16_t value)
{
    node_frame_put_byte(node, (uint8_t)(value & BYTE_MASK));
    node_frame_put_byte(node, (uint8_t)(value >> BYTE_BITS));
}

void node_frame_put_string(node_state *node, const char *text, uint8_t length)
{
    uint8_t i;

    node_frame_put_byte(node, length);
    for (i = 0; i < length; i++)
        node_frame_put_byte(node, (uint8_t)text[i]);
}

void node_frame_end(node_state *node)
{
    while (node->transmit_left > 0)
        node_frame_put_byte(node, 0);
    flush(node, true);
}

uint8_t node_string_length(const char *text)
{
    uint16_t length = 0;

    if (text == NULL)
        return 0;
    while (length < NODE_MAX_STRING && text[length] != '\0')
        length++;
    // Cut before a character, not inside one, when the text goes on.
    if (text[length] != '\0') {
        while (length > 0 &&
               ((uint8_t)text[length] & UTF8_CONTINUATION_MASK) == UTF8_CONTINUATION_VALUE)
            length--;
    }
    return (uint8_t)length;
}

void node_send_words(node_state *node, uint16_t type, const uint16_t *words, uint16_t count)
{
    uint16_t i;

    if (count > NODE_MAX_PAYLOAD / 2)
        count = NODE_MAX_PAYLOAD / 2;
    node_frame_begin(node, type, (uint16_t)(count * 2));
    for (i = 0; i < count; i++)
        node_frame_put_u16(node, words[i]);
    node_frame_end(node);
}

void node_send_word_and_string(node_state *node, uint16_t type, uint16_t word, const char *text)
{
    uint8_t length = node_string_length(text);

    node_frame_begin(node, type, (uint16_t)(2 + 1 + length));
    node_frame_put_u16(node, word);
    node_frame_put_string(node, text, length);
    node_frame_end(node);
}

void node_send_variables(node_state *node, uint16_t start, uint16_t length)
{
    uint16_t size = node->vm.memory.variables_size;
    const int16_t *variables = node->vm.memory.variables;
    uint16_t count = start < size ? (uint16_t)(size - start) : 0;

    if (count > length)
        count = length;
    // Always one answer, empty when nothing of the range exists, so that a
    // host waiting for it is not left waiting.
    do {
        uint16_t part = count < NODE_MAX_VARIABLES_WORDS ? count : NODE_MAX_VARIABLES_WORDS;
        uint16_t i;

        node_frame_begin(node, NODE_MSG_VARIABLES, (uint16_t)(2 + part * 2));
        node_frame_put_u16(node, start);
        for (i = 0; i < part; i++)
            node_frame_put_u16(node, (uint16_t)variables[start + i]);
        node_frame_end(node);
        start = (uint16_t)(start + part);
        count = (uint16_t)(count - part);
    } while (count > 0);
}

void node_send_user_event(node_state *node, uint16_t event, const int16_t *payload, uint16_t count)
{
    // Types from 0x8000 are not user events; node_send_words keeps the 258
    // words hosts allow. Signed words go on the wire as their bits.
    if (event < NODE_FIRST_SYSTEM_TYPE)
        node_send_words(node, event, (const uint16_t *)payload, count);
}

// --- the VM's reports --------------------------------------------------------

static void on_emit(void *context, uint16_t event, const int16_t *payload, uint16_t count)
{
    node_send_user_event((node_state *)context, event, payload, count);
}

// The VM's reports are coded as their message types (vm.h).
typedef char reports_are_message_types
  [VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS == NODE_MSG_ARRAY_ACCESS_OUT_OF_BOUNDS &&
       VM_REPORT_DIVISION_BY_ZERO == NODE_MSG_DIVISION_BY_ZERO &&
       VM_REPORT_EVENT_EXECUTION_KILLED == NODE_MSG_EVENT_EXECUTION_KILLED &&
       VM_REPORT_EXECUTION_STATE_CHANGED == NODE_MSG_EXECUTION_STATE_CHANGED
     ? 1
     : -1];

static void on_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    node_send_words((node_state *)context, type, words, count);
}

static void on_node_specific_error(void *context, uint16_t pc, const char *message)
{
    node_send_word_and_string((node_state *)context, NODE_MSG_NODE_SPECIFIC_ERROR, pc, message);
}

const vm_callbacks node_vm_callbacks = {
    on_emit,
    on_report,
    on_node_specific_error,
};
