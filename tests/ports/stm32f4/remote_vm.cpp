// vm.h for the host tests, run by the harness image in QEMU: each function
// is one call to the firmware's VM on the emulated Cortex-M4, its effects
// brought back into the caller's vm_state and memory, its messages to the
// caller's callbacks. Linked instead of the VM library, it runs the VM tests
// unchanged on the microcontroller's instruction set.

#include <cstring>

#include "tests/ports/stm32f4/remote_link.hpp"

using qemu_test::Bytes;
using qemu_test::fail;
using qemu_test::Reader;
using qemu_test::RemoteMachine;
using qemu_test::Writer;

namespace
{

// Reads `count` words at `reader` and hands them to the VM's report
// callback as report `type`.
void report(vm_state *vm, uint16_t type, Reader &reader, uint16_t count)
{
    uint16_t words[3] = {};
    for (uint16_t i = 0; i < count; ++i)
        words[i] = reader.u16();
    vm->callbacks->report(vm->context, type, words, count);
}

// Hands the events at `reader` to the VM's callbacks, in order; returns at
// the first one that is not the VM's (a node's), or at the end, with that
// event's kind.
uint8_t dispatch_vm_events(vm_state *vm, Reader &reader)
{
    const vm_callbacks *callbacks = vm->callbacks;
    for (;;) {
        uint8_t kind = reader.u8();
        switch (kind) {
        case REMOTE_EVENT_EMIT: {
            uint16_t event = reader.u16();
            std::vector<int16_t> payload(reader.u16());
            for (int16_t &word : payload)
                word = int16_t(reader.u16());
            callbacks->emit(vm->context, event, payload.data(), uint16_t(payload.size()));
            break;
        }
        case REMOTE_EVENT_STATE: report(vm, VM_REPORT_EXECUTION_STATE_CHANGED, reader, 2); break;
        case REMOTE_EVENT_KILLED: report(vm, VM_REPORT_EVENT_EXECUTION_KILLED, reader, 1); break;
        case REMOTE_EVENT_ARRAY: report(vm, VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS, reader, 3); break;
        case REMOTE_EVENT_DIVISION: report(vm, VM_REPORT_DIVISION_BY_ZERO, reader, 1); break;
        case REMOTE_EVENT_NODE_ERROR: {
            uint16_t pc = reader.u16();
            std::string text(reader.u8(), '\0');
            for (char &c : text)
                c = char(reader.u8());
            callbacks->node_specific_error(vm->context, pc, text.c_str());
            break;
        }
        default: return kind;
        }
    }
}

uint16_t call(vm_state *vm, const Writer &arguments)
{
    return qemu_test::call_vm(vm, arguments);
}

uint16_t call(vm_state *vm, uint8_t which)
{
    Writer writer;
    writer.u8(which);
    return call(vm, writer);
}

uint16_t call(vm_state *vm, uint8_t which, uint16_t argument)
{
    Writer writer;
    writer.u8(which);
    writer.u16(argument);
    return call(vm, writer);
}

// The harness VM's natives (tests/support/vm_harness.cpp) are the only
// table the image has for a bare VM.
bool is_harness_table(const vm_native_table *natives)
{
    return natives != nullptr && vm_native_count(natives) == 12 &&
           std::strcmp(vm_native_name(vm_native_at(natives, 0)), "test.subtract") == 0;
}

} // namespace

uint16_t qemu_test::call_vm(vm_state *vm, const Writer &arguments)
{
    uint16_t result;
    Bytes answer = RemoteMachine::instance().call(arguments, &result);
    Reader reader{ answer, 2 };
    if (dispatch_vm_events(vm, reader) != REMOTE_EVENT_END)
        fail("a bare VM sent a node's event");
    RemoteMachine::instance().take_changes(reader);
    return result;
}

extern "C" {

void vm_init(vm_state *vm,
             const vm_memory *memory,
             uint16_t node_id,
             const vm_native_table *natives,
             const vm_callbacks *callbacks,
             void *context)
{
    if (!is_harness_table(natives))
        fail("the image knows only the harness natives of tests/support/vm_harness.cpp");
    std::memset(vm, 0, sizeof *vm);
    vm->memory = *memory;
    vm->natives = *natives;
    vm->callbacks = callbacks;
    vm->context = context;
    Bytes answer =
      RemoteMachine::instance().open(REMOTE_OPEN_VM, REMOTE_NATIVES_HARNESS, vm, node_id);
    Reader reader{ answer };
    RemoteMachine::instance().take_changes(reader);
}

uint16_t vm_event_address(const vm_state *vm, uint16_t event)
{
    return call(const_cast<vm_state *>(vm), REMOTE_VM_EVENT_ADDRESS, event);
}

uint16_t vm_setup_event(vm_state *vm, uint16_t event)
{
    return call(vm, REMOTE_VM_SETUP_EVENT, event);
}

void vm_receive_event(vm_state *vm,
                      uint16_t event,
                      uint16_t source,
                      const int16_t *payload,
                      uint16_t count)
{
    Writer writer;
    writer.u8(REMOTE_VM_RECEIVE_EVENT);
    writer.u16(event);
    writer.u16(source);
    writer.u16(count);
    for (uint16_t i = 0; i < count; i++)
        writer.u16(uint16_t(payload[i]));
    call(vm, writer);
}

bool vm_run(vm_state *vm, uint16_t step_budget)
{
    return call(vm, REMOTE_VM_RUN, step_budget) != 0;
}

bool vm_step(vm_state *vm)
{
    return call(vm, REMOTE_VM_STEP) != 0;
}

void vm_set_bytecode(vm_state *vm, uint16_t start, const uint16_t *words, uint16_t count)
{
    Writer writer;
    writer.u8(REMOTE_VM_SET_BYTECODE);
    writer.u16(start);
    writer.u16(count);
    for (uint16_t i = 0; i < count; i++)
        writer.u16(words[i]);
    call(vm, writer);
}

void vm_reset(vm_state *vm)
{
    call(vm, REMOTE_VM_RESET);
}

void vm_command_run(vm_state *vm)
{
    call(vm, REMOTE_VM_COMMAND_RUN);
}

void vm_command_pause(vm_state *vm)
{
    call(vm, REMOTE_VM_COMMAND_PAUSE);
}

void vm_command_step(vm_state *vm)
{
    call(vm, REMOTE_VM_COMMAND_STEP);
}

void vm_command_stop(vm_state *vm)
{
    call(vm, REMOTE_VM_COMMAND_STOP);
}

void vm_report_state(vm_state *vm)
{
    call(vm, REMOTE_VM_REPORT_STATE);
}

bool vm_breakpoint_set(vm_state *vm, uint16_t pc)
{
    return call(vm, REMOTE_VM_BREAKPOINT_SET, pc) != 0;
}

void vm_breakpoint_clear(vm_state *vm, uint16_t pc)
{
    call(vm, REMOTE_VM_BREAKPOINT_CLEAR, pc);
}

void vm_breakpoint_clear_all(vm_state *vm)
{
    call(vm, REMOTE_VM_BREAKPOINT_CLEAR_ALL);
}

// Natives run on the target only.
int16_t *vm_variables(vm_state *, uint16_t, uint16_t)
{
    fail("a native function ran on the host");
}

void vm_error_array_access(vm_state *, uint16_t, uint16_t)
{
    fail("a native function ran on the host");
}

void vm_error_division_by_zero(vm_state *)
{
    fail("a native function ran on the host");
}

void vm_error_node_specific(vm_state *, const char *)
{
    fail("a native function ran on the host");
}

} // extern "C"
