// What the VM's files share among themselves: the texts of its errors and
// the load-time verifier that vm_reset runs.

#ifndef VM_INTERNAL_H
#define VM_INTERNAL_H

#include "vm.h"

// Texts of the NODE_SPECIFIC_ERROR reports (bytecode.md §8.5), sent when a
// run reaches the fault or, for faults the verifier finds, when a host asks
// a rejected program to run.
extern const char vm_error_stack_overflow[];
extern const char vm_error_stack_underflow[];
extern const char vm_error_variables_bounds[];
extern const char vm_error_bytecode_bounds[];
extern const char vm_error_unknown_bytecode[];
extern const char vm_error_unknown_operator[];
extern const char vm_error_unknown_native[];
extern const char vm_error_event_too_large[];
extern const char vm_error_invalid_jump[];

// Sends report `type` (VM_REPORT_...) of `count` words, 1 or 2: the pc,
// then `second`.
void vm_report(vm_state *vm, uint16_t type, uint16_t count, uint16_t second);

// For RUN and STEP of a program the verifier refused: reports why, at the
// faulty instruction, as a run-time error (which stops the VM).
void vm_report_rejection(vm_state *vm);

// Verifies the bytecode (vm_verify.c) and clears the was-true bit of every
// conditional branch it reaches. Sets vm->rejection to NULL when the program
// is safe to run without the checks the verifier made, else to the text of
// the first fault found and vm->rejection_pc to its place. Uses the stack
// memory as scratch: no event may be active.
void vm_verify(vm_state *vm);

#endif
