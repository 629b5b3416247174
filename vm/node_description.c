// What a node says about itself: the description sequence of protocol.md
// §6.1 (DESCRIPTION, then named variables, local events, native functions)
// and its fingerprint (§9).
//
// Every string is cut to what the wire allows. A native function's message
// holds two strings and a name per parameter, packed (vm.h) and expanded as
// they are sent; a broken table's native whose message would exceed the
// 516-byte payload is described by its name alone.

#include "node_internal.h"

#include <stddef.h>

// DESCRIPTION after its name: version, bytecode, stack and variables sizes,
// and the three counts, uint16 each.
#define DESCRIPTION_FIXED_BYTES 14
// NATIVE_FUNCTION_DESCRIPTION: the two string length bytes and the
// parameter count; each parameter: its size and its name's length byte.
#define NATIVE_FIXED_BYTES     4
#define NATIVE_PARAMETER_BYTES 3

#define BYTE_MASK 0xFF
#define BYTE_BITS 8

// A native's packed description (vm.h) split into the parts of its message.
typedef struct native_parts {
    const char *documentation; // NULL when it has none
    const char *parameters;    // the first parameter's size byte
    uint16_t parameter_count;
    uint16_t payload_length;
} native_parts;

// The length of a text of a description (NULL: an empty one), cut to 255.
static uint8_t text_length(const char *words, const char *text)
{
    vm_native_text reader = { words, text, NULL };
    uint8_t length = 0;

    if (text != NULL) {
        while (length < NODE_MAX_STRING && vm_native_text_next(&reader) != 0)
            length++;
    }
    return length;
}

// The parameter after the one at `parameter` (its size byte).
static const char *next_parameter(const char *parameter)
{
    return vm_native_text_end(parameter + 1);
}

static int16_t parameter_size(const char *parameter)
{
    return (int16_t)((uint8_t)*parameter - VM_NATIVE_SIZE_BIAS);
}

// Splits `description` into `parts` (through a pointer: a returned struct
// costs 16-bit chips a copy). Texts are cut to 255 bytes. A native whose
// message would still exceed the payload limit (a broken table) is
// described by its name alone.
static void split_native(const char *words, const char *description, native_parts *parts)
{
    const char *end = vm_native_text_end(description);

    parts->documentation = NULL;
    if ((uint8_t)*end == VM_NATIVE_DOCUMENTATION_MARK) {
        parts->documentation = end + 1;
        end = vm_native_text_end(parts->documentation);
    }
    parts->parameters = end;
    parts->parameter_count = 0;
    parts->payload_length = (uint16_t)(NATIVE_FIXED_BYTES + text_length(words, description) +
                                       text_length(words, parts->documentation));
    for (; *end != '\0'; end = next_parameter(end)) {
        parts->payload_length += NATIVE_PARAMETER_BYTES + text_length(words, end + 1);
        parts->parameter_count++;
    }
    if (parts->payload_length > NODE_MAX_PAYLOAD) {
        parts->documentation = NULL;
        parts->parameter_count = 0;
        parts->payload_length = (uint16_t)(NATIVE_FIXED_BYTES + text_length(words, description));
    }
}

// A text of a description (or NULL: an empty one) as a protocol string.
static void put_text(node_state *node, const char *text)
{
    vm_native_text reader = { node->vm.natives.words, text, NULL };
    uint8_t length = text_length(reader.words, text);

    node_frame_put_byte(node, length);
    while (length-- > 0)
        node_frame_put_byte(node, vm_native_text_next(&reader));
}

static void send_native(node_state *node, const vm_native *native)
{
    native_parts parts;
    const char *parameter;
    uint16_t i;

    split_native(node->vm.natives.words, vm_native_name(native), &parts);
    parameter = parts.parameters;
    node_frame_begin(node, NODE_MSG_NATIVE_FUNCTION_DESCRIPTION, parts.payload_length);
    put_text(node, vm_native_name(native));
    put_text(node, parts.documentation);
    node_frame_put_u16(node, parts.parameter_count);
    for (i = 0; i < parts.parameter_count; i++) {
        node_frame_put_u16(node, (uint16_t)parameter_size(parameter));
        put_text(node, parameter + 1);
        parameter = next_parameter(parameter);
    }
    node_frame_end(node);
}

// The description's frames: DESCRIPTION, the named variables, the local
// events, the natives.
static uint16_t description_frame_count(const node_state *node)
{
    return (uint16_t)(1u + node->description->variable_count +
                      node->description->local_event_count + vm_native_count(&node->vm.natives));
}

// Sends the description's frame number `index` (0: DESCRIPTION).
static void send_description_frame(node_state *node, uint16_t index)
{
    const node_description *description = node->description;
    const vm_memory *memory = &node->vm.memory;
    uint8_t length;

    if (index == 0) {
        length = node_string_length(description->name);
        node_frame_begin(
          node, NODE_MSG_DESCRIPTION, (uint16_t)(1 + length + DESCRIPTION_FIXED_BYTES));
        node_frame_put_string(node, description->name, length);
        node_frame_put_u16(node, description->protocol_version);
        node_frame_put_u16(node, memory->bytecode_size);
        node_frame_put_u16(node, memory->stack_size);
        node_frame_put_u16(node, memory->variables_size);
        node_frame_put_u16(node, description->variable_count);
        node_frame_put_u16(node, description->local_event_count);
        node_frame_put_u16(node, vm_native_count(&node->vm.natives));
        node_frame_end(node);
        return;
    }
    index--;
    if (index < description->variable_count) {
        const node_named_variable *variable = &description->variables[index];

        node_send_word_and_string(
          node, NODE_MSG_NAMED_VARIABLE_DESCRIPTION, variable->size, variable->name);
        return;
    }
    index = (uint16_t)(index - description->variable_count);
    if (index < description->local_event_count) {
        const node_local_event *event = &description->local_events[index];
        uint8_t name_length = node_string_length(event->name);

        length = node_string_length(event->description);
        node_frame_begin(
          node, NODE_MSG_LOCAL_EVENT_DESCRIPTION, (uint16_t)(1 + name_length + 1 + length));
        node_frame_put_string(node, event->name, name_length);
        node_frame_put_string(node, event->description, length);
        node_frame_end(node);
        return;
    }
    index = (uint16_t)(index - description->local_event_count);
    send_native(node, vm_native_at(&node->vm.natives, index));
}

void node_start_description(node_state *node)
{
    // One asked while another is being sent follows it whole: a host that
    // collects the frames may be counting those of the first.
    if (node->description_left != 0) {
        node->description_again = true;
        return;
    }
    node->description_next = 0;
    node->description_left = description_frame_count(node);
}

bool node_continue_description(node_state *node)
{
    if (node->description_left == 0)
        return false;
    send_description_frame(node, node->description_next);
    node->description_next++;
    node->description_left--;
    if (node->description_left == 0 && node->description_again) {
        node->description_again = false;
        node_start_description(node);
    }
    return true;
}

// --- fingerprint -------------------------------------------------------------

static uint16_t crc_u16(uint16_t crc, uint16_t value)
{
    uint8_t bytes[2];

    bytes[0] = (uint8_t)(value & BYTE_MASK);
    bytes[1] = (uint8_t)(value >> BYTE_BITS);
    return node_crc16(crc, bytes, 2);
}

// A string counts with a zero byte after it when its length is odd.
static uint16_t crc_string(uint16_t crc, const char *text, uint8_t length)
{
    static const uint8_t padding = 0;

    crc = node_crc16(crc, (const uint8_t *)text, length);
    if (length & 1)
        crc = node_crc16(crc, &padding, 1);
    return crc;
}

// A text of a native's description, as crc_string counts strings.
static uint16_t crc_text(uint16_t crc, const char *words, const char *text)
{
    static const uint8_t padding = 0;
    vm_native_text reader = { words, text, NULL };
    uint8_t length = text_length(words, text);
    uint8_t i;

    for (i = 0; i < length; i++) {
        uint8_t byte = vm_native_text_next(&reader);

        crc = node_crc16(crc, &byte, 1);
    }
    if (length & 1)
        crc = node_crc16(crc, &padding, 1);
    return crc;
}

uint16_t node_description_fingerprint(const node_description *description,
                                      uint16_t bytecode_size,
                                      uint16_t stack_size,
                                      uint16_t variables_size)
{
    uint16_t crc = 0;
    uint16_t count = description->natives != NULL ? vm_native_count(description->natives) : 0;
    uint16_t i;
    uint16_t j;

    // This order (variables before stack) is the fingerprint's, not the wire's.
    crc = crc_u16(crc, bytecode_size);
    crc = crc_u16(crc, variables_size);
    crc = crc_u16(crc, stack_size);
    for (i = 0; i < description->variable_count; i++) {
        const node_named_variable *variable = &description->variables[i];

        crc = crc_u16(crc, variable->size);
        crc = crc_string(crc, variable->name, node_string_length(variable->name));
    }
    for (i = 0; i < description->local_event_count; i++) {
        const char *name = description->local_events[i].name;

        crc = crc_string(crc, name, node_string_length(name));
    }
    for (i = 0; i < count; i++) {
        const char *words = description->natives->words;
        const char *name = vm_native_name(vm_native_at(description->natives, i));
        native_parts parts;
        const char *parameter;

        split_native(words, name, &parts);
        parameter = parts.parameters;
        crc = crc_text(crc, words, name);
        for (j = 0; j < parts.parameter_count; j++) {
            crc = crc_u16(crc, (uint16_t)parameter_size(parameter));
            crc = crc_text(crc, words, parameter + 1);
            parameter = next_parameter(parameter);
        }
    }
    return crc;
}

uint16_t node_fingerprint(const node_state *node)
{
    const vm_memory *memory = &node->vm.memory;

    return node_description_fingerprint(
      node->description, memory->bytecode_size, memory->stack_size, memory->variables_size);
}
