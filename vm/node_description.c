// What a node says about itself: the description sequence of protocol.md
// §6.1 (DESCRIPTION, then named variables, local events, native functions)
// and its fingerprint (§9).
//
// Every string is cut to what the wire allows. A native function's message
// holds two strings and a name per parameter, which may together exceed the
// 516-byte payload; its name is then kept whole, parameter names come next
// and the description gets what is left. (A table with more parameters than
// fit at all is broken; the node then sends as many as fit.)

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

static uint16_t native_count(const node_state *node)
{
    return node->vm.natives.natives != NULL ? node->vm.natives.count : 0;
}

// The lengths a native function's strings get on the wire.
typedef struct native_layout {
    uint16_t parameter_count;
    uint8_t name_length;
    uint8_t description_length;
    uint16_t payload_length;
} native_layout;

// Parameter names share what the name leaves, in order; returns the length
// of parameter `index`'s name and takes it from `*room`.
static uint8_t parameter_name_length(const vm_native *native, uint16_t index, uint16_t *room)
{
    uint8_t length = node_string_length(native->parameters[index].name, *room);

    *room = (uint16_t)(*room - length);
    return length;
}

// The room parameter names start with: what the name and the parameters'
// fixed bytes leave of the payload.
static uint16_t parameter_room(const native_layout *layout)
{
    return (uint16_t)(NODE_MAX_PAYLOAD - NATIVE_FIXED_BYTES -
                      NATIVE_PARAMETER_BYTES * layout->parameter_count - layout->name_length);
}

static native_layout layout_native(const vm_native *native)
{
    native_layout layout;
    uint16_t count = native->parameters != NULL ? native->parameter_count : 0;
    uint16_t most;
    uint16_t room;
    uint16_t i;

    layout.name_length = node_string_length(native->name, NODE_MAX_STRING);
    // Only a broken table has more parameters than a message can hold.
    most = (uint16_t)((NODE_MAX_PAYLOAD - NATIVE_FIXED_BYTES - layout.name_length) /
                      NATIVE_PARAMETER_BYTES);
    layout.parameter_count = count < most ? count : most;
    room = parameter_room(&layout);
    for (i = 0; i < layout.parameter_count; i++)
        parameter_name_length(native, i, &room);
    layout.description_length = node_string_length(native->description, room);
    room = (uint16_t)(room - layout.description_length);
    layout.payload_length = (uint16_t)(NODE_MAX_PAYLOAD - room);
    return layout;
}

static void send_native(node_state *node, const vm_native *native)
{
    native_layout layout = layout_native(native);
    uint16_t room = parameter_room(&layout);
    uint16_t i;

    node_frame_begin(node, NODE_MSG_NATIVE_FUNCTION_DESCRIPTION, layout.payload_length);
    node_frame_put_string(node, native->name, layout.name_length);
    node_frame_put_string(node, native->description, layout.description_length);
    node_frame_put_u16(node, layout.parameter_count);
    for (i = 0; i < layout.parameter_count; i++) {
        const vm_native_parameter *parameter = &native->parameters[i];
        uint8_t length = parameter_name_length(native, i, &room);

        node_frame_put_u16(node, (uint16_t)parameter->size);
        node_frame_put_string(node, parameter->name, length);
    }
    node_frame_end(node);
}

void node_send_description(node_state *node)
{
    const node_description *description = node->description;
    const vm_memory *memory = &node->vm.memory;
    uint8_t length = node_string_length(description->name, NODE_MAX_STRING);
    uint16_t i;

    node_frame_begin(node, NODE_MSG_DESCRIPTION, (uint16_t)(1 + length + DESCRIPTION_FIXED_BYTES));
    node_frame_put_string(node, description->name, length);
    node_frame_put_u16(node, description->protocol_version);
    node_frame_put_u16(node, memory->bytecode_size);
    node_frame_put_u16(node, memory->stack_size);
    node_frame_put_u16(node, memory->variables_size);
    node_frame_put_u16(node, description->variable_count);
    node_frame_put_u16(node, description->local_event_count);
    node_frame_put_u16(node, native_count(node));
    node_frame_end(node);

    for (i = 0; i < description->variable_count; i++) {
        const node_named_variable *variable = &description->variables[i];

        node_send_word_and_string(
          node, NODE_MSG_NAMED_VARIABLE_DESCRIPTION, variable->size, variable->name);
    }

    for (i = 0; i < description->local_event_count; i++) {
        const node_local_event *event = &description->local_events[i];
        uint8_t name_length = node_string_length(event->name, NODE_MAX_STRING);

        length = node_string_length(event->description, NODE_MAX_STRING);
        node_frame_begin(
          node, NODE_MSG_LOCAL_EVENT_DESCRIPTION, (uint16_t)(1 + name_length + 1 + length));
        node_frame_put_string(node, event->name, name_length);
        node_frame_put_string(node, event->description, length);
        node_frame_end(node);
    }

    for (i = 0; i < native_count(node); i++)
        send_native(node, node->vm.natives.natives[i]);
}

// --- fingerprint -------------------------------------------------------------

#define CRC16_POLYNOMIAL 0x1021
#define CRC16_TOP_BIT    0x8000

uint16_t node_crc16(uint16_t crc, const uint8_t *bytes, uint16_t count)
{
    uint16_t i;
    uint8_t bit;

    for (i = 0; i < count; i++) {
        crc ^= (uint16_t)((uint16_t)bytes[i] << BYTE_BITS);
        for (bit = 0; bit < BYTE_BITS; bit++) {
            if (crc & CRC16_TOP_BIT)
                crc = (uint16_t)((uint16_t)(crc << 1) ^ CRC16_POLYNOMIAL);
            else
                crc = (uint16_t)(crc << 1);
        }
    }
    return crc;
}

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

uint16_t node_description_fingerprint(const node_description *description,
                                      uint16_t bytecode_size,
                                      uint16_t stack_size,
                                      uint16_t variables_size)
{
    uint16_t crc = 0;
    uint16_t count = description->natives != NULL && description->natives->natives != NULL
                       ? description->natives->count
                       : 0;
    uint16_t i;
    uint16_t j;

    // This order (variables before stack) is the fingerprint's, not the wire's.
    crc = crc_u16(crc, bytecode_size);
    crc = crc_u16(crc, variables_size);
    crc = crc_u16(crc, stack_size);
    for (i = 0; i < description->variable_count; i++) {
        const node_named_variable *variable = &description->variables[i];

        crc = crc_u16(crc, variable->size);
        crc = crc_string(crc, variable->name, node_string_length(variable->name, NODE_MAX_STRING));
    }
    for (i = 0; i < description->local_event_count; i++) {
        const char *name = description->local_events[i].name;

        crc = crc_string(crc, name, node_string_length(name, NODE_MAX_STRING));
    }
    for (i = 0; i < count; i++) {
        const vm_native *native = description->natives->natives[i];
        native_layout layout = layout_native(native);
        uint16_t room = parameter_room(&layout);

        crc = crc_string(crc, native->name, layout.name_length);
        for (j = 0; j < layout.parameter_count; j++) {
            uint8_t length = parameter_name_length(native, j, &room);

            crc = crc_u16(crc, (uint16_t)native->parameters[j].size);
            crc = crc_string(crc, native->parameters[j].name, length);
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
