// An Aseba node: the VM on a wire that speaks protocol 5 (protocol.md).
//
// The node is transport-neutral: the caller feeds it the bytes it receives
// (with the time), calls node_poll from its main loop, and gives it a send
// function for the bytes it emits. The same code serves the e-puck's UART and
// a TCP socket on a PC. Like the VM it has no globals and no allocation; RAM
// is one receive buffer of the largest frame plus a small transmit chunk:
// outgoing frames are streamed, never built whole.
//
// Receiving. A stream has no start marker or checksum (§2): the node reads 6
// header bytes then `len` payload bytes. A frame is dropped, and counted, when
//   - it stalls: its next byte comes more than NODE_INTER_BYTE_TIMEOUT_MS
//     after the previous one (a truncated frame is only seen this way);
//   - its length is larger than 516: the position in the stream is then
//     lost, so the node throws away every byte until the line has been quiet
//     for NODE_INTER_BYTE_TIMEOUT_MS, and reads a header again. That is the
//     only resynchronisation a stream allows; a connection-oriented transport
//     may rather close the connection when `errors.oversize` grows;
//   - its payload is too short, or odd, for its type (every host-to-node
//     layout is made of 16-bit words).
// At most one complete frame waits for node_poll; while it waits node_receive
// consumes nothing more, and the caller keeps the rest for later.

#ifndef NODE_H
#define NODE_H

#include <stdbool.h>
#include <stdint.h>

#include "node_config.h"
#include "node_crc.h"
#include "node_protocol.h"
#include "vm.h"

typedef struct node_named_variable {
    const char *name;
    uint16_t size; // words
} node_named_variable;

typedef struct node_local_event {
    const char *name;
    const char *description;
} node_local_event;

// What a node tells hosts about itself (protocol.md §5.2-§5.5). Memory sizes
// come from the VM's memory. Strings longer than 255 bytes are cut at a
// character boundary when sent.
typedef struct node_description {
    const char *name;
    uint16_t protocol_version; // NODE_PROTOCOL_VERSION
    // In memory order: the first is at address 0. Variables 0, 1 and 2 must
    // be the id, the event source and the event arguments (bytecode.md §7).
    const node_named_variable *variables;
    uint16_t variable_count;
    // Local event i has event id 0xFFFE - i.
    const node_local_event *local_events;
    uint16_t local_event_count;
    // In NATIVE_CALL order; may be NULL when the node has none.
    const vm_native_table *natives;
} node_description;

// Where outgoing bytes go. A frame arrives in one or more consecutive calls;
// `frame_complete` is true on its last piece (a TCP transport may gather the
// pieces and write once). The node blocks for as long as `send` does.
typedef struct node_transport {
    void (*send)(void *context, const uint8_t *bytes, uint16_t count, bool frame_complete);
    void *context;
} node_transport;

// Firmware services reached by host commands (protocol.md §6.8). Any of them
// may be NULL: the command is then ignored.
typedef struct node_hooks {
    // WRITE_BYTECODE: store the bytecode so that it runs at the next boot.
    void (*write_bytecode)(void *context, const uint16_t *bytecode, uint16_t size);
    // REBOOT: restart the microcontroller (into the bootloader if any).
    void (*reboot)(void *context);
    // SUSPEND_TO_RAM: sleep until a device-specific wake-up.
    void (*suspend_to_ram)(void *context);
    void *context;
} node_hooks;

// Frames and bytes the node threw away, by cause. Each counter stops at
// 0xFFFF instead of wrapping.
typedef struct node_error_counters {
    uint16_t oversize;          // announced length above 516
    uint16_t truncated;         // partial frame stalled past the timeout
    uint16_t malformed;         // payload too short or odd for its type
    uint16_t wrong_destination; // addressed to another node (normal on a bus)
    uint16_t ignored;           // types a node does not handle (bootloader,
                                // other nodes' messages, unknown)
} node_error_counters;

typedef struct node_state {
    vm_state vm;
    const node_description *description;
    node_transport transport;
    node_hooks hooks;

    // Receiving: the frame being assembled, as words so that the payload,
    // converted in place, can be handed to the VM as int16 words.
    uint16_t frame[NODE_MAX_FRAME / 2];
    uint16_t received;     // bytes of `frame` filled so far
    bool frame_ready;      // a whole frame waits for node_poll
    bool resynchronising;  // dropping bytes until the line is quiet
    uint32_t last_byte_ms; // time of the last byte taken

    // Sending: the current piece of the outgoing frame.
    uint8_t transmit[NODE_TRANSMIT_CHUNK];
    uint16_t transmit_fill;
    uint16_t transmit_left; // bytes the frame being sent still owes

    // The description being sent, a frame per node_poll.
    uint16_t description_next; // the next frame's number (0: DESCRIPTION)
    uint16_t description_left; // frames still to send
    bool description_again;    // asked for once more meanwhile

    uint32_t pending_local_events; // bit i: local event i was raised
    node_error_counters errors;
} node_state;

// Most local events a node can have (bits of pending_local_events).
#define NODE_MAX_LOCAL_EVENTS 32

// Prepares a node with id `node_id` (1..0xFFFE; 0 is the hosts' id) around a
// fresh VM over `memory`. Stores the id in variable 0 and takes the size of
// `args` from the description's third variable. `hooks` may be NULL. The
// description, the memory and the native table must outlive the node.
void node_init(node_state *node,
               uint16_t node_id,
               const node_description *description,
               const vm_memory *memory,
               const node_transport *transport,
               const node_hooks *hooks);

// Feeds received bytes to the frame assembler, at time `now_ms` (any
// millisecond clock that may wrap). Returns how many bytes it took: fewer
// than `count` when a complete frame waits for node_poll; the caller passes
// the rest again after polling.
uint16_t node_receive(node_state *node, const uint8_t *bytes, uint16_t count, uint32_t now_ms);

// Feeds one byte; returns false (and takes nothing) while a frame waits.
bool node_receive_byte(node_state *node, uint8_t byte, uint32_t now_ms);

// Whether node_receive_byte would take a byte now: false while a complete
// frame waits for node_poll. A caller that takes bytes from a buffer of its
// own (a UART's ring) asks first, and leaves them there until then.
bool node_receive_ready(const node_state *node);

// How many bytes node_receive would take now at time `now_ms`, all of them
// (it first drops a stalled partial frame, as node_receive would): what the
// frame lacks, 0 while a complete frame waits. Lets a caller take that many
// from its own buffer at once.
uint16_t node_receive_wanted(node_state *node, uint32_t now_ms);

// Where the bytes node_receive_wanted just asked for go, so that a caller
// copies them there from its own buffer once instead of through one of its
// own and node_receive. Then node_receive_placed says how many it put there,
// no more than asked for, at the same `now_ms`, and answers what
// node_receive_wanted would answer next.
uint8_t *node_receive_place(node_state *node);
uint16_t node_receive_placed(node_state *node, uint16_t count, uint32_t now_ms);

// One step of the main loop, never blocking (bytecode.md §6.5): discards a
// stalled partial frame, runs the VM for at most NODE_STEP_BUDGET
// instructions, handles the waiting frame if any, then starts the lowest
// pending local event if no event is active. Returns whether there is more
// to do right away; when false the caller may sleep until the next input.
bool node_poll(node_state *node, uint32_t now_ms);

// Marks local event `index` pending (it starts in node_poll, after the active
// handler ends). Call it from the context that calls node_poll. Returns false
// for an index the description does not have.
bool node_raise_local_event(node_state *node, uint16_t index);

// Sends a user event from the firmware itself, as EMIT would: at most 258
// words are sent; an event id from 0x8000 (not a user event) sends nothing.
void node_send_user_event(node_state *node, uint16_t event, const int16_t *payload, uint16_t count);

// The description fingerprint of protocol.md §9 (CRC-16/XMODEM over sizes and
// names as the node sends them), for this node.
uint16_t node_fingerprint(const node_state *node);

// The same for a description and memory sizes, without a node.
uint16_t node_description_fingerprint(const node_description *description,
                                      uint16_t bytecode_size,
                                      uint16_t stack_size,
                                      uint16_t variables_size);

#endif
