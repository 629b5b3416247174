#include "our_node.hpp"

#include <algorithm>
#include <cstddef>
#include <map>
#include <stdexcept>

#include "tools/compiler/target_presets.hpp"

namespace
{

OurNode &node_of(void *context)
{
    return *static_cast<OurNode *>(context);
}

void ignore_emit(void *, uint16_t, const int16_t *, uint16_t) {}

void record_array_access(void *context, uint16_t pc, uint16_t size, uint16_t index)
{
    node_of(context).errors.push_back({ ErrorReport::Kind::array_access, pc, size, index, {} });
}

void record_division_by_zero(void *context, uint16_t pc)
{
    node_of(context).errors.push_back({ ErrorReport::Kind::division_by_zero, pc, 0, 0, {} });
}

void record_node_specific(void *context, uint16_t pc, const char *message)
{
    node_of(context).errors.push_back({ ErrorReport::Kind::node_specific, pc, 0, 0, message });
}

// Records the errors among the VM's word reports; state changes and killed
// events are not errors.
void record_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    if (type == VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS && count == 3)
        record_array_access(context, words[0], words[1], words[2]);
    else if (type == VM_REPORT_DIVISION_BY_ZERO && count == 1)
        record_division_by_zero(context, words[0]);
    else if (type != VM_REPORT_EXECUTION_STATE_CHANGED && type != VM_REPORT_EVENT_EXECUTION_KILLED)
        record_node_specific(context, count > 0 ? words[0] : 0, "unexpected report");
}

const vm_callbacks recording_callbacks = { ignore_emit, record_report, record_node_specific };

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
    vm_init(&vm, &memory, 1, &nat_standard_table, &recording_callbacks, this);
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
