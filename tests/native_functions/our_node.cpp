#include "our_node.hpp"

#include <algorithm>
#include <cstddef>
#include <map>
#include <stdexcept>

#include "tools/compiler/target_presets.hpp"

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
    vm_memory memory{};
    memory.bytecode = bytecode_.data();
    memory.bytecode_size = bytecode_words;
    memory.variables = variables.data();
    memory.variables_size = variables_size;
    memory.stack = stack_.data();
    memory.stack_size = stack_words;
    memory.args_size = 0;
    vm_init(&vm, &memory, 1, &nat_standard_table, &our_node_callbacks, this);
}

void OurNode::call(const vm_native &native, const std::vector<int16_t> &popped_words)
{
    if (popped_words.size() != vm_native_stack_words(&native))
        throw std::invalid_argument("wrong argument count for " + description_of(native).name);
    // vm_init copied the memory description; keep it pointing at our vector.
    vm.memory.variables = variables.data();
    vm.pc = call_pc;
    vm.flags = VM_FLAG_EVENT_ACTIVE | VM_FLAG_EVENT_RUNNING;
    native.function(&vm, popped_words.data());
}

void OurNode::put(uint16_t address, const std::vector<int16_t> &values)
{
    for (size_t i = 0; i < values.size(); ++i)
        variables.at(address + i) = values[i];
}

std::vector<int16_t> OurNode::get(uint16_t address, uint16_t count) const
{
    return std::vector<int16_t>(variables.begin() + address, variables.begin() + address + count);
}

void OurNode::run_init(const std::vector<uint16_t> &bytecode)
{
    vm.memory.variables = variables.data();
    if (bytecode.size() > bytecode_.size())
        throw std::invalid_argument("bytecode too long");
    // Uploaded as a host does, so that the verifier sees it; then run.
    vm_set_bytecode(&vm, 0, bytecode.data(), static_cast<uint16_t>(bytecode.size()));
    if (vm.rejection != nullptr)
        throw std::invalid_argument(std::string("bytecode refused: ") + vm.rejection);
    if (!vm_is_event_active(&vm) || vm.pc != vm_event_address(&vm, init_event))
        throw std::invalid_argument("bytecode does not handle init");
    vm.flags = VM_FLAG_EVENT_ACTIVE;
    vm_run(&vm, 0);
}
