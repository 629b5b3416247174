// The node's main loop: assembling frames from a byte stream, handling the
// host's messages (protocol.md §6.3) and starting local events (bytecode.md
// §6.5). Outgoing messages are in node_send.c and node_description.c.

#include "node_internal.h"
#include "vm_opcodes.h"

#include <stddef.h>

#define BYTE_BITS 8

// Payload bytes each host command needs (protocol.md §3): `dest` and the
// fields after it.
#define BYTES_FIRST_WORD   2 // dest, or the version of a broadcast
#define BYTES_DEST_AND_ONE 4
#define BYTES_DEST_AND_TWO 6

// Payload word positions of addressed commands.
#define PAYLOAD_DEST   0
#define PAYLOAD_FIRST  1 // start, pc or version
#define PAYLOAD_SECOND 2 // length, or the first word of data

static void count_error(uint16_t *counter)
{
    if (*counter < UINT16_MAX)
        (*counter)++;
}

static bool timed_out(const node_state *node, uint32_t now_ms)
{
    return (uint32_t)(now_ms - node->last_byte_ms) > NODE_INTER_BYTE_TIMEOUT_MS;
}

void node_init(node_state *node,
               uint16_t node_id,
               const node_description *description,
               const vm_memory *memory,
               const node_transport *transport,
               const node_hooks *hooks)
{
    static const vm_native_table no_natives = { NULL, 0, NULL };
    uint8_t *bytes = (uint8_t *)node;
    uint16_t i;

    // Every counter, flag and buffer starts at zero; absent hooks are NULL.
    for (i = 0; i < sizeof *node; i++)
        bytes[i] = 0;
    vm_init(&node->vm,
            memory,
            node_id,
            description->natives != NULL ? description->natives : &no_natives,
            &node_vm_callbacks,
            node);
    // `args` is the third named variable (bytecode.md §7).
    if (description->variable_count > VM_NAMED_ARGS)
        node->vm.memory.args_size = description->variables[VM_NAMED_ARGS].size;
    // The first named variable holds the node id (protocol.md §8.4).
    if (node->vm.memory.variables_size > 0)
        node->vm.memory.variables[0] = (int16_t)node_id;

    node->description = description;
    node->transport = *transport;
    if (hooks != NULL)
        node->hooks = *hooks;
}

// --- receiving ---------------------------------------------------------------

static uint16_t frame_word(const node_state *node, uint16_t index)
{
    const uint8_t *bytes = (const uint8_t *)node->frame;

    return (uint16_t)(bytes[2 * index] | (uint16_t)bytes[2 * index + 1] << BYTE_BITS);
}

// Drops a partial frame that has waited too long, or ends a resynchronisation
// once the line has been quiet that long.
static void expire_partial_frame(node_state *node, uint32_t now_ms)
{
    if (node->frame_ready || !timed_out(node, now_ms))
        return;
    if (node->resynchronising) {
        node->resynchronising = false;
    } else if (node->received > 0) {
        count_error(&node->errors.truncated);
        node->received = 0;
    }
}

bool node_receive_ready(const node_state *node)
{
    return !node->frame_ready;
}

// What the frame lacks: the header, then the payload it announces.
static uint16_t bytes_lacking(const node_state *node)
{
    if (node->frame_ready)
        return 0;
    // While resynchronising, bytes are dropped one by one until a silence.
    if (node->resynchronising)
        return 1;
    if (node->received < NODE_HEADER_SIZE)
        return (uint16_t)(NODE_HEADER_SIZE - node->received);
    return (uint16_t)(NODE_HEADER_SIZE + frame_word(node, FRAME_LENGTH) - node->received);
}

uint16_t node_receive_wanted(node_state *node, uint32_t now_ms)
{
    if (node->frame_ready)
        return 0;
    expire_partial_frame(node, now_ms);
    return bytes_lacking(node);
}

uint8_t *node_receive_place(node_state *node)
{
    return (uint8_t *)node->frame + node->received;
}

// `count` bytes, no more than node_receive_wanted asked for, are now in
// place at the frame's end: a header that announces too long a payload
// starts a resynchronisation, a frame complete waits for node_poll.
static void frame_grew(node_state *node, uint16_t count)
{
    node->received = (uint16_t)(node->received + count);
    if (node->received < NODE_HEADER_SIZE)
        return;
    if (frame_word(node, FRAME_LENGTH) > NODE_MAX_PAYLOAD) {
        count_error(&node->errors.oversize);
        node->received = 0;
        node->resynchronising = true;
    } else if (node->received == NODE_HEADER_SIZE + frame_word(node, FRAME_LENGTH)) {
        node->frame_ready = true;
    }
}

uint16_t node_receive_placed(node_state *node, uint16_t count, uint32_t now_ms)
{
    if (count == 0)
        return node_receive_wanted(node, now_ms);
    node->last_byte_ms = now_ms;
    // While resynchronising, the byte in place is dropped.
    if (!node->resynchronising)
        frame_grew(node, count);
    // A byte came at now_ms: nothing partial has expired.
    return bytes_lacking(node);
}

uint16_t node_receive(node_state *node, const uint8_t *bytes, uint16_t count, uint32_t now_ms)
{
    uint16_t taken = 0;

    // A part at a time: the header, then the payload its length announces
    // (what node_receive_wanted asks for), not a byte at a time.
    while (taken < count) {
        uint16_t part = node_receive_wanted(node, now_ms);
        uint8_t *place = node_receive_place(node);
        uint16_t i;

        if (part == 0)
            break;
        node->last_byte_ms = now_ms;
        if (node->resynchronising) { // dropped until a silence
            taken = count;
            break;
        }
        if (part > count - taken)
            part = (uint16_t)(count - taken);
        for (i = 0; i < part; i++)
            place[i] = bytes[taken + i];
        taken = (uint16_t)(taken + part);
        frame_grew(node, part);
    }
    return taken;
}

bool node_receive_byte(node_state *node, uint8_t byte, uint32_t now_ms)
{
    return node_receive(node, &byte, 1, now_ms) == 1;
}

// --- handling a frame --------------------------------------------------------

// Turns the little-endian frame, header and payload, into native words where
// it lies, so that the payload can be handed to the VM.
static void to_native_words(node_state *node)
{
    uint16_t count = (uint16_t)(FRAME_PAYLOAD + frame_word(node, FRAME_LENGTH) / 2);
    uint16_t i;

    for (i = 0; i < count; i++)
        node->frame[i] = frame_word(node, i);
}

// Bytes the payload of host command `type` needs at least.
static uint16_t command_minimum_length(uint16_t type)
{
    switch (type) {
    case NODE_MSG_SET_BYTECODE:
    case NODE_MSG_BREAKPOINT_SET:
    case NODE_MSG_BREAKPOINT_CLEAR:
    case NODE_MSG_SET_VARIABLES:
    case NODE_MSG_GET_NODE_DESCRIPTION: return BYTES_DEST_AND_ONE;
    case NODE_MSG_GET_VARIABLES: return BYTES_DEST_AND_TWO;
    default: return BYTES_FIRST_WORD;
    }
}

static void set_variables(node_state *node, uint16_t start, const uint16_t *values, uint16_t count)
{
    uint16_t size = node->vm.memory.variables_size;
    uint16_t room = start < size ? (uint16_t)(size - start) : 0;
    uint16_t i;

    // Writes beyond the memory are ignored (protocol.md §6.6).
    if (count > room)
        count = room;
    for (i = 0; i < count; i++)
        node->vm.memory.variables[start + i] = (int16_t)values[i];
}

static void set_breakpoint(node_state *node, uint16_t pc)
{
    uint16_t answer[2];

    answer[0] = pc;
    answer[1] = vm_breakpoint_set(&node->vm, pc) ? 1 : 0;
    node_send_words(node, NODE_MSG_BREAKPOINT_SET_RESULT, answer, 2);
}

// An addressed command (0xA001-0xA010) that passed the dest and length checks.
static void handle_command(node_state *node, uint16_t type, const uint16_t *payload, uint16_t words)
{
    vm_state *vm = &node->vm;
    const node_hooks *hooks = &node->hooks;

    switch (type) {
    case NODE_MSG_SET_BYTECODE:
        vm_set_bytecode(
          vm, payload[PAYLOAD_FIRST], payload + PAYLOAD_SECOND, (uint16_t)(words - PAYLOAD_SECOND));
        break;
    case NODE_MSG_RESET: vm_reset(vm); break;
    case NODE_MSG_RUN: vm_command_run(vm); break;
    case NODE_MSG_PAUSE: vm_command_pause(vm); break;
    case NODE_MSG_STEP: vm_command_step(vm); break;
    case NODE_MSG_STOP: vm_command_stop(vm); break;
    case NODE_MSG_GET_EXECUTION_STATE: vm_report_state(vm); break;
    case NODE_MSG_BREAKPOINT_SET: set_breakpoint(node, payload[PAYLOAD_FIRST]); break;
    case NODE_MSG_BREAKPOINT_CLEAR: vm_breakpoint_clear(vm, payload[PAYLOAD_FIRST]); break;
    case NODE_MSG_BREAKPOINT_CLEAR_ALL: vm_breakpoint_clear_all(vm); break;
    case NODE_MSG_GET_VARIABLES:
        node_send_variables(node, payload[PAYLOAD_FIRST], payload[PAYLOAD_SECOND]);
        break;
    case NODE_MSG_SET_VARIABLES:
        set_variables(node,
                      payload[PAYLOAD_FIRST],
                      payload + PAYLOAD_SECOND,
                      (uint16_t)(words - PAYLOAD_SECOND));
        break;
    case NODE_MSG_WRITE_BYTECODE:
        if (hooks->write_bytecode != NULL)
            hooks->write_bytecode(hooks->context, vm->memory.bytecode, vm->memory.bytecode_size);
        break;
    case NODE_MSG_REBOOT:
        if (hooks->reboot != NULL)
            hooks->reboot(hooks->context);
        break;
    case NODE_MSG_SUSPEND_TO_RAM:
        if (hooks->suspend_to_ram != NULL)
            hooks->suspend_to_ram(hooks->context);
        break;
    case NODE_MSG_GET_NODE_DESCRIPTION: node_start_description(node); break;
    default: break;
    }
}

static void handle_frame(node_state *node)
{
    const uint16_t *payload = node->frame + FRAME_PAYLOAD;
    uint16_t length, source, type, words;

    to_native_words(node);
    length = node->frame[FRAME_LENGTH];
    source = node->frame[FRAME_SOURCE];
    type = node->frame[FRAME_TYPE];
    words = (uint16_t)(length / 2);

    // Bootloader messages, other nodes' messages and unknown types.
    if (type >= NODE_FIRST_SYSTEM_TYPE &&
        (type < NODE_MSG_GET_DESCRIPTION || type > NODE_MSG_LIST_NODES)) {
        count_error(&node->errors.ignored);
        return;
    }
    // Every layout a node reads is made of 16-bit words.
    if (length & 1) {
        count_error(&node->errors.malformed);
        return;
    }

    if (type < NODE_FIRST_SYSTEM_TYPE) {
        vm_receive_event(&node->vm, type, source, (const int16_t *)payload, words);
        return;
    }
    // Every system message starts with a word: the host's protocol version in
    // the two broadcasts, `dest` in the others.
    if (length < BYTES_FIRST_WORD) {
        count_error(&node->errors.malformed);
        return;
    }
    if (type == NODE_MSG_LIST_NODES || type == NODE_MSG_GET_DESCRIPTION) {
        uint16_t version = NODE_PROTOCOL_VERSION;

        if (type == NODE_MSG_LIST_NODES)
            node_send_words(node, NODE_MSG_NODE_PRESENT, &version, 1);
        else if (payload[0] <= NODE_OLDEST_DESCRIPTION_VERSION)
            node_start_description(node);
        return;
    }
    if (payload[PAYLOAD_DEST] != node->vm.node_id) {
        count_error(&node->errors.wrong_destination);
        return;
    }
    if (length < command_minimum_length(type)) {
        count_error(&node->errors.malformed);
        return;
    }
    handle_command(node, type, payload, words);
}

// --- the main loop -----------------------------------------------------------

bool node_raise_local_event(node_state *node, uint16_t index)
{
    if (index >= node->description->local_event_count || index >= NODE_MAX_LOCAL_EVENTS)
        return false;
    node->pending_local_events |= (uint32_t)1 << index;
    return true;
}

// Starts the lowest pending local event once no handler is active, so that
// local events wait for each other instead of killing one another.
static void start_local_event(node_state *node)
{
    uint16_t index = 0;
    uint32_t bit = 1;

    if (node->pending_local_events == 0 || vm_is_event_active(&node->vm))
        return;
    while (!(node->pending_local_events & bit)) {
        bit <<= 1;
        index++;
    }
    node->pending_local_events &= ~bit;
    if (node->vm.memory.variables_size > VM_NAMED_SOURCE)
        node->vm.memory.variables[VM_NAMED_SOURCE] = (int16_t)node->vm.node_id;
    vm_setup_event(&node->vm, (uint16_t)(VM_EVENT_LOCAL_FIRST - index));
}

bool node_poll(node_state *node, uint32_t now_ms)
{
    const vm_state *vm = &node->vm;
    bool running;
    bool describing;

    expire_partial_frame(node, now_ms);
    vm_run(&node->vm, NODE_STEP_BUDGET);
    // A description goes out only at a poll that found no received frame,
    // NODE_DESCRIPTION_FRAMES_PER_POLL frames at a time: on a slow link,
    // sending all of it (some 65 frames, 0.17 s at 115,200 baud) at once
    // would leave a robot's receive buffer to fill meanwhile with what other
    // robots and hosts send. Received frames are handled first, one a poll.
    if (node->frame_ready) {
        handle_frame(node);
        node->frame_ready = false;
        node->received = 0;
    } else {
        uint16_t sent = 0;
        while (sent < NODE_DESCRIPTION_FRAMES_PER_POLL && node_continue_description(node))
            sent++;
    }
    describing = node->description_left != 0;
    start_local_event(node);

    running = vm_is_event_active(vm) && !(vm->flags & VM_FLAG_STEP_BY_STEP);
    return running || describing || (node->pending_local_events != 0 && !vm_is_event_active(vm));
}
