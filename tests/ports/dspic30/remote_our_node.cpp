// OurNode (tests/native_functions/our_node.hpp) on the dsPIC30F: its VM is
// the harness image's, with the e-puck's natives (the standard ones first,
// so with the same ids); direct calls run there too (REMOTE_VM_CALL_NATIVE).
// Linked instead of our_node.cpp, it runs the standard natives' tests
// unchanged on the chip's machine code, as remote_dsp_node.cpp does the DSP
// natives'. A node is a VM of the image's (remote_epuck_vm.hpp); a test's
// second node takes the image over in turn, its memory sent again.

#include <cstring>
#include <stdexcept>
#include <string>

#include "tests/native_functions/our_node.hpp"
#include "tests/ports/dspic30/remote_epuck_vm.hpp"
#include "tests/ports/stm32f4/remote_link.hpp"

namespace
{

constexpr uint16_t bytecode_words = 64;
constexpr uint16_t init_event = 0xFFFF;
constexpr uint16_t stack_words = 32;

} // namespace

OurNode::OurNode(uint16_t variables_size)
  : variables(variables_size)
  , bytecode_(bytecode_words)
  , stack_(stack_words)
{
    std::memset(&vm, 0, sizeof vm);
    vm.memory.bytecode = bytecode_.data();
    vm.memory.bytecode_size = bytecode_words;
    vm.memory.variables = variables.data();
    vm.memory.variables_size = variables_size;
    vm.memory.stack = stack_.data();
    vm.memory.stack_size = stack_words;
    vm.memory.args_size = 0;
    vm.node_id = 1;
    vm.natives = dspic30_test::epuck_like_table;
    vm.callbacks = &our_node_callbacks;
    vm.context = this;
    dspic30_test::open_epuck_vm(vm);
}

void OurNode::call(const vm_native &native, const std::vector<int16_t> &popped_words)
{
    if (popped_words.size() != vm_native_stack_words(&native))
        throw std::invalid_argument("wrong argument count for " + description_of(native).name);
    const std::optional<uint16_t> index = dspic30_test::epuck_index(native);
    if (!index)
        qemu_test::fail("a native the image does not have");
    dspic30_test::call_epuck_native(vm, *index, call_pc, popped_words);
}

void OurNode::put(uint16_t address, const std::vector<int16_t> &values)
{
    for (size_t i = 0; i < values.size(); ++i)
        variables.at(address + i) = values[i];
}

std::vector<int16_t> OurNode::get(uint16_t address, uint16_t count) const
{
    if (address + count > variables.size())
        throw std::out_of_range("OurNode::get");
    return std::vector<int16_t>(variables.begin() + address, variables.begin() + address + count);
}

void OurNode::run_init(const std::vector<uint16_t> &bytecode)
{
    if (bytecode.size() > bytecode_.size())
        throw std::invalid_argument("bytecode too long");
    dspic30_test::use_epuck_vm(vm);
    // Uploaded as a host does, so that the verifier sees it; then run.
    vm_set_bytecode(&vm, 0, bytecode.data(), static_cast<uint16_t>(bytecode.size()));
    if (!vm_is_event_active(&vm) || vm.pc != vm_event_address(&vm, init_event))
        throw std::invalid_argument("bytecode does not handle init");
    vm.flags = VM_FLAG_EVENT_ACTIVE;
    vm_run(&vm, 0);
}
