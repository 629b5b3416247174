// What a host can do to a node's VM from outside: load bytecode, control
// execution, set breakpoints, deliver events (bytecode.md §6.3, §6.4, §7).
// Each command sends the answer that protocol 5 hosts expect.

#include "vm_internal.h"
#include "vm_opcodes.h"

#include <stddef.h>

void vm_report_state(vm_state *vm)
{
    vm_report(vm, VM_REPORT_EXECUTION_STATE_CHANGED, 2, vm->flags);
}

void vm_reset(vm_state *vm)
{
    vm->flags = VM_FLAG_STEP_BY_STEP;
    vm_verify(vm);
    // With STEP_BY_STEP set, setting up init reports (init address, 3).
    if (vm_setup_event(vm, VM_EVENT_INIT) == 0)
        vm_report_state(vm);
}

void vm_set_bytecode(vm_state *vm, uint16_t start, const uint16_t *words, uint16_t count)
{
    uint16_t size = vm->memory.bytecode_size;
    uint16_t room = start < size ? (uint16_t)(size - start) : 0;
    uint16_t i;

    // Words beyond the node's bytecode are ignored, as upstream hosts expect.
    if (count > room)
        count = room;
    for (i = 0; i < count; i++)
        vm->memory.bytecode[start + i] = words[i];
    vm_reset(vm);
}

void vm_command_run(vm_state *vm)
{
    if (vm->rejection != NULL) {
        vm_report_rejection(vm);
    } else {
        vm->flags &= (uint16_t)~VM_FLAG_STEP_BY_STEP;
    }
    vm_report_state(vm);
}

void vm_command_pause(vm_state *vm)
{
    vm->flags |= VM_FLAG_STEP_BY_STEP;
    vm_report_state(vm);
}

void vm_command_step(vm_state *vm)
{
    if (vm_step(vm))
        vm_report_state(vm);
}

void vm_command_stop(vm_state *vm)
{
    vm->flags = VM_FLAG_STEP_BY_STEP;
    vm_report_state(vm);
}

bool vm_breakpoint_set(vm_state *vm, uint16_t pc)
{
    if (vm->breakpoint_count >= VM_MAX_BREAKPOINTS || pc >= vm->memory.bytecode_size)
        return false;
    vm->breakpoints[vm->breakpoint_count++] = pc;
    return true;
}

void vm_breakpoint_clear(vm_state *vm, uint16_t pc)
{
    uint16_t i;

    for (i = 0; i < vm->breakpoint_count; i++) {
        if (vm->breakpoints[i] == pc) {
            vm->breakpoint_count--;
            for (; i < vm->breakpoint_count; i++)
                vm->breakpoints[i] = vm->breakpoints[i + 1];
            return;
        }
    }
}

void vm_breakpoint_clear_all(vm_state *vm)
{
    vm->breakpoint_count = 0;
}

void vm_receive_event(vm_state *vm,
                      uint16_t event,
                      uint16_t source,
                      const int16_t *payload,
                      uint16_t count)
{
    uint16_t size = vm->memory.variables_size;
    uint16_t room = size > VM_NAMED_ARGS ? (uint16_t)(size - VM_NAMED_ARGS) : 0;
    uint16_t i;

    // While a user steps through a handler, network events are dropped.
    if ((vm->flags & VM_FLAG_STEP_BY_STEP) && (vm->flags & VM_FLAG_EVENT_ACTIVE))
        return;
    if (size > VM_NAMED_SOURCE)
        vm->memory.variables[VM_NAMED_SOURCE] = (int16_t)source;
    // The payload is copied even when no handler exists, as upstream does.
    if (count > vm->memory.args_size)
        count = vm->memory.args_size;
    if (count > room)
        count = room;
    for (i = 0; i < count; i++)
        vm->memory.variables[VM_NAMED_ARGS + i] = payload[i];
    vm_setup_event(vm, event);
}
