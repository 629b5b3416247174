// The Aseba virtual machine: runs protocol-5 bytecode in memory that the
// caller owns, reports to the node through callbacks, never touches hardware.
//
// One struct holds the whole state; there are no globals and no allocation,
// so a host process can run hundreds of robots side by side. No bytecode can
// make the VM reach outside its memory: a verifier checks each program when
// it arrives (vm_reset), so that the run loop only checks what depends on
// run-time values; a faulty program is refused or stops its event and is
// reported, and the VM stays usable.

#ifndef VM_H
#define VM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vm_config.h"

// Execution flags (bytecode.md §6), also sent as they are in
// EXECUTION_STATE_CHANGED messages.
#define VM_FLAG_EVENT_ACTIVE  0x0001 // a handler is executing: pc is valid
#define VM_FLAG_STEP_BY_STEP  0x0002 // paused, or stopped after an error
#define VM_FLAG_EVENT_RUNNING 0x0004 // inside vm_run

// Protocol limits that are part of the bytecode's contract, not tunables.
#define VM_MAX_BREAKPOINTS   16  // the wire protocol's table size
#define VM_MAX_EVENT_WORDS   258 // largest payload of one emitted event
#define VM_NAMED_SOURCE      1   // address of `source`, set on each event
#define VM_NAMED_ARGS        2   // address of `args`, filled from event payloads
#define VM_NODE_ERROR_LENGTH 255 // longest NODE_SPECIFIC_ERROR text

typedef struct vm_state vm_state;

// The reports whose payloads are words (protocol.md §5), the pc first. The
// codes are the protocol's message types, so that a node sends a report as
// it comes: one callback instead of one per report, less code on both sides.
#define VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS 0x9006 // pc, size, index; the VM is stopped
#define VM_REPORT_DIVISION_BY_ZERO           0x9007 // pc; the VM is stopped
#define VM_REPORT_EVENT_EXECUTION_KILLED     0x9008 // pc: a new event abandoned the running one
#define VM_REPORT_EXECUTION_STATE_CHANGED    0x900A // pc, flags

// What the VM tells the node. Each callback receives the `context` given at
// vm_init. Payloads are those of protocol.md §5.
typedef struct vm_callbacks {
    // EMIT: a user event with `count` words, to every other node and host.
    void (*emit)(void *context, uint16_t event, const int16_t *payload, uint16_t count);
    // A report of type VM_REPORT_..., with its `count` words.
    void (*report)(void *context, uint16_t type, const uint16_t *words, uint16_t count);
    // NODE_SPECIFIC_ERROR(pc, message); the VM is stopped.
    void (*node_specific_error)(void *context, uint16_t pc, const char *message);
} vm_callbacks;

// A native function. Before the call the VM has popped the function's
// stack words (vm_native_stack_words) into `arguments` (arguments[0] was
// the top of the stack); the function reaches variables only through
// vm_variables().
typedef void (*vm_native_function)(vm_state *vm, const int16_t *arguments);

// A native function as a node's table lists it: its C function and its
// description, one packed string so that a table costs a few bytes per
// native. The description starts with the native's stack words, one byte
// (parameters + size words, bytecode.md §9; at most VM_MAX_NATIVE_ARGUMENTS),
// then says what NATIVE_FUNCTION_DESCRIPTION says of it (protocol.md §5.5):
//
//   stack-words name [ VM_NATIVE_DOCUMENTATION_MARK documentation ]
//   { size parameter-name }
//
// Texts are bytes from VM_NATIVE_TEXT_FIRST (0x20); in a table with a
// dictionary (vm_native_table.words) each byte from VM_NATIVE_WORD_FIRST
// (0x80) stands for a word of it. A parameter starts with its size plus
// VM_NATIVE_SIZE_BIAS, one byte below 0x20: sizes -15 to 14 (> 0 fixed, < 0
// template id, 0 any size). vm_native_text expands a text. Keeping the stack
// words in the string rather than in a field of their own saves the field's
// padding: a record is two pointers.
typedef struct vm_native {
    vm_native_function function;
    const char *description;
} vm_native;

// The words the VM pops for `native`.
static inline uint16_t vm_native_stack_words(const vm_native *native)
{
    return (uint8_t)native->description[0];
}

// The description of `native` from its name on.
static inline const char *vm_native_name(const vm_native *native)
{
    return native->description + 1;
}

#define VM_NATIVE_DOCUMENTATION_MARK 0x1F
#define VM_NATIVE_SIZE_BIAS          0x10
#define VM_NATIVE_TEXT_FIRST         0x20
#define VM_NATIVE_WORD_FIRST         0x80

// The natives of one module (a file of natives), in their NATIVE_CALL order
// within it: the file lists its records at its end and counts them with
// sizeof, so that a native is added in its own file alone.
typedef struct vm_native_module {
    const vm_native *natives;
    uint16_t count;
} vm_native_module;

// The natives a node exports: its modules' natives one after the other, in
// NATIVE_CALL order (a native's id is its place in that concatenation); the
// same order is sent in NATIVE_FUNCTION_DESCRIPTION messages. Tables are
// data: a target lists the modules it exports (robots/epuck/epuck_natives.c,
// nat_standard.h). Modules, not one flat array, because C cannot gather
// records from several files into one array; a call walks a handful of
// modules (vm_native_at).
typedef struct vm_native_table {
    const vm_native_module *const *modules;
    uint16_t module_count;
    // The words of the descriptions' bytes from VM_NATIVE_WORD_FIRST, in
    // order, each ended by a NUL, the last by two; NULL when those bytes
    // stand for themselves.
    const char *words;
} vm_native_table;

// Native `id` of `table`, or NULL when the table has fewer natives. Inline,
// as vm_native_count: the VM's NATIVE_CALL finds its native here, and the
// tests' stand-ins for the VM read tables without linking it.
static inline const vm_native *vm_native_at(const vm_native_table *table, uint16_t id)
{
    uint16_t module;

    for (module = 0; module < table->module_count; module++) {
        const vm_native_module *natives = table->modules[module];

        if (id < natives->count)
            return &natives->natives[id];
        id -= natives->count;
    }
    return NULL;
}

// The number of natives of `table`, its modules' together.
static inline uint16_t vm_native_count(const vm_native_table *table)
{
    uint16_t count = 0;
    uint16_t module;

    for (module = 0; module < table->module_count; module++)
        count += table->modules[module]->count;
    return count;
}

// Where the text that starts at `text` in a packed description ends: at the
// documentation mark, a parameter's size or the description's NUL.
const char *vm_native_text_end(const char *text);

// Reads a text of a packed description byte by byte, its words expanded:
// start with { the table's words (or NULL), the text, NULL }.
typedef struct vm_native_text {
    const char *words;
    const char *text; // the next byte of the text
    const char *word; // the next byte of the word being expanded, or NULL
} vm_native_text;

// The text's next byte, or 0 after its last.
uint8_t vm_native_text_next(vm_native_text *reader);

// Memory the caller gives the VM; it must outlive the VM. The bytecode is
// the VM's: write it with vm_set_bytecode, or call vm_reset after writing it
// directly, so that the verifier sees it before it runs.
typedef struct vm_memory {
    uint16_t *bytecode;
    uint16_t bytecode_size;
    int16_t *variables;
    uint16_t variables_size;
    int16_t *stack;
    uint16_t stack_size;
    uint16_t args_size; // size of the `args` named variable at VM_NAMED_ARGS
} vm_memory;

struct vm_state {
    uint16_t node_id;
    uint16_t pc;
    int16_t sp; // index of the top of the stack, -1 when empty
    uint16_t flags;
    uint16_t breakpoint_count;
    uint16_t breakpoints[VM_MAX_BREAKPOINTS];
    uint16_t random_state; // of math.rand, per node
    vm_memory memory;
    vm_native_table natives;
    const vm_callbacks *callbacks;
    void *context;
    // The verifier's verdict on the bytecode (vm_reset): NULL when it may
    // run, else why not (reported at rejection_pc when a host sends RUN or
    // STEP).
    const char *rejection;
    uint16_t rejection_pc;
};

// Prepares a VM over `memory`: an empty event table (bytecode[0] = 0), all
// variables zero, no event active (flags 0). The stack memory is also the
// verifier's scratch.
void vm_init(vm_state *vm,
             const vm_memory *memory,
             uint16_t node_id,
             const vm_native_table *natives,
             const vm_callbacks *callbacks,
             void *context);

// Address of the handler of `event`, or 0 when the bytecode does not handle it.
uint16_t vm_event_address(const vm_state *vm, uint16_t event);

// Starts the handler of `event` (killing, and reporting, an active one).
// Returns its address, or 0 and changes nothing when it is not handled.
uint16_t vm_setup_event(vm_state *vm, uint16_t event);

// Delivers a user event from the network (bytecode.md §7): sets `source`,
// copies the payload into `args` (clamped to its size) and sets up the handler.
// Does nothing while paused inside an event.
void vm_receive_event(vm_state *vm,
                      uint16_t event,
                      uint16_t source,
                      const int16_t *payload,
                      uint16_t count);

// Runs the active event until it ends, an error or a breakpoint stops it, or
// `step_budget` instructions have run (0: no limit). Returns whether anything
// ran; a handler cut by the budget goes on at the next call.
bool vm_run(vm_state *vm, uint16_t step_budget);

// Executes exactly one instruction of the active event, ignoring breakpoints.
// Returns false when no event is active.
bool vm_step(vm_state *vm);

// Whether an event handler is executing or waiting to continue.
static inline bool vm_is_event_active(const vm_state *vm)
{
    return (vm->flags & VM_FLAG_EVENT_ACTIVE) != 0;
}

// The debug commands of bytecode.md §6.4, each with its protocol answer.
// vm_reset (and so vm_set_bytecode) verifies the bytecode and clears the
// was-true bit of its conditional branches (`when` starts false). Events are
// set up and answered as upstream does whatever the verdict (a program
// arrives in chunks, the first ones incomplete), but a refused program never
// runs: RUN or STEP reports why, at the faulty instruction, and stops.
void vm_set_bytecode(vm_state *vm, uint16_t start, const uint16_t *words, uint16_t count);
void vm_reset(vm_state *vm);
void vm_command_run(vm_state *vm);
void vm_command_pause(vm_state *vm);
void vm_command_step(vm_state *vm);
void vm_command_stop(vm_state *vm);
void vm_report_state(vm_state *vm);

// Breakpoints: set answers whether it was stored (room left, pc inside the
// bytecode); clear removes the first entry at pc.
bool vm_breakpoint_set(vm_state *vm, uint16_t pc);
void vm_breakpoint_clear(vm_state *vm, uint16_t pc);
void vm_breakpoint_clear_all(vm_state *vm);

// For natives and firmware: `length` variables from `address`, or NULL after
// stopping the VM with an "out of variables bounds" error when they do not
// fit. An empty span is always granted (and must not be accessed).
int16_t *vm_variables(vm_state *vm, uint16_t address, uint16_t length);

// For natives and firmware: stop the VM and report an error at the current pc.
void vm_error_array_access(vm_state *vm, uint16_t size, uint16_t index);
void vm_error_division_by_zero(vm_state *vm);
void vm_error_node_specific(vm_state *vm, const char *message);

#endif
