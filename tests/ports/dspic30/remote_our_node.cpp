// OurNode (tests/native_functions/our_node.hpp) on the dsPIC30F: its VM is
// the harness image's, with the e-puck's natives (the standard ones first,
// so with the same ids); direct calls run there too (REMOTE_VM_CALL_NATIVE).
// Linked instead of our_node.cpp, it runs the standard natives' tests
// unchanged on the chip's machine code, as remote_dsp_node.cpp does the DSP
// natives'. A node is a VM of the image's; a test's second node takes the
// image over in turn, its memory sent again.

#include <cstring>
#include <stdexcept>
#include <string>

#include "tests/native_functions/our_node.hpp"
#include "tests/ports/stm32f4/remote_link.hpp"

extern "C" {
#include "nat_dsp.h"
#include "nat_words.h"
}

using qemu_test::Bytes;
using qemu_test::fail;
using qemu_test::Reader;
using qemu_test::RemoteMachine;
using qemu_test::Writer;

namespace
{

OurNode &node_of(void *context)
{
    return *static_cast<OurNode *>(context);
}

void ignore_emit(void *, uint16_t, const int16_t *, uint16_t) {}

// As our_node.cpp's: the errors among the VM's reports.
void record_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    OurNode &node = node_of(context);
    if (type == VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS && count == 3)
        node.errors.push_back(
          { ErrorReport::Kind::array_access, words[0], words[1], words[2], {} });
    else if (type == VM_REPORT_DIVISION_BY_ZERO && count == 1)
        node.errors.push_back({ ErrorReport::Kind::division_by_zero, words[0], 0, 0, {} });
    else if (type != VM_REPORT_EXECUTION_STATE_CHANGED && type != VM_REPORT_EVENT_EXECUTION_KILLED)
        node.errors.push_back({ ErrorReport::Kind::node_specific,
                                count > 0 ? words[0] : uint16_t(0),
                                0,
                                0,
                                "unexpected report" });
}

void record_node_specific(void *context, uint16_t pc, const char *message)
{
    node_of(context).errors.push_back({ ErrorReport::Kind::node_specific, pc, 0, 0, message });
}

const vm_callbacks recording_callbacks = { ignore_emit, record_report, record_node_specific };

// The host's copy of the image's table: to find a native's index, and for
// the verifier's view of the bytecode (vm_state.natives).
const vm_native_module *const epuck_like_modules[] = { NAT_STANDARD_MODULES NAT_DSP_MODULES };
const vm_native_table epuck_like_table = { epuck_like_modules,
                                           uint16_t(std::size(epuck_like_modules)),
                                           nat_words };

constexpr uint16_t bytecode_words = 64;
constexpr uint16_t init_event = 0xFFFF;
constexpr uint16_t stack_words = 32;

// The image runs one VM at a time: the node whose VM it holds.
const OurNode *open_node = nullptr;

// Gives the image `node`'s VM (its memory as the host holds it) unless it
// has it already: a test may compare two nodes.
void open(OurNode &node)
{
    if (open_node == &node)
        return;
    Bytes answer =
      RemoteMachine::instance().open(REMOTE_OPEN_VM, REMOTE_NATIVES_EPUCK, &node.vm, 1);
    Reader reader{ answer };
    RemoteMachine::instance().take_changes(reader);
    open_node = &node;
}

// The index REMOTE_VM_CALL_NATIVE takes for `native`: its place in the table.
uint16_t remote_index(const vm_native &native)
{
    const uint16_t count = vm_native_count(&epuck_like_table);
    for (uint16_t i = 0; i < count; ++i)
        if (vm_native_at(&epuck_like_table, i)->function == native.function)
            return i;
    fail("a native the image does not have");
}

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
    vm.natives = epuck_like_table;
    vm.callbacks = &recording_callbacks;
    vm.context = this;
    open_node = nullptr;
    open(*this);
}

void OurNode::call(const vm_native &native, const std::vector<int16_t> &popped_words)
{
    if (popped_words.size() != vm_native_stack_words(&native))
        throw std::invalid_argument("wrong argument count for " + description_of(native).name);
    open(*this);
    Writer writer;
    writer.u8(REMOTE_VM_CALL_NATIVE);
    writer.u16(remote_index(native));
    writer.u16(call_pc);
    writer.u16(uint16_t(popped_words.size()));
    for (int16_t word : popped_words)
        writer.u16(uint16_t(word));
    if (qemu_test::call_vm(&vm, writer) == 0)
        fail("the image refused a native call");
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
    open(*this);
    // Uploaded as a host does, so that the verifier sees it; then run.
    vm_set_bytecode(&vm, 0, bytecode.data(), static_cast<uint16_t>(bytecode.size()));
    if (!vm_is_event_active(&vm) || vm.pc != vm_event_address(&vm, init_event))
        throw std::invalid_argument("bytecode does not handle init");
    vm.flags = VM_FLAG_EVENT_ACTIVE;
    vm_run(&vm, 0);
}
