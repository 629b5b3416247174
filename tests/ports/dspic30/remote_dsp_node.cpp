// DspNode (tests/native_functions_dsp/dsp_node.hpp) on the dsPIC30F: its VM
// is the harness image's, with the e-puck's natives as the application
// has them (the DSP natives on the port's DSP-engine kernel,
// ports/dspic30/dspic30_dsp_kernel.c); direct calls run there too
// (REMOTE_VM_CALL_NATIVE). Linked instead of dsp_node.cpp, it runs the DSP
// natives' tests unchanged on the chip's machine code.

#include <cstring>
#include <stdexcept>
#include <string>

#include "tests/native_functions_dsp/dsp_node.hpp"
#include "tests/ports/dspic30/remote_epuck_vm.hpp"
#include "tests/ports/stm32f4/remote_link.hpp"

extern "C" {
// The tests' deliberately faulty FFT (dsp_fft_truncating_mutant.c), which
// the image has too, after the e-puck's table.
extern const vm_native_module nat_dsp_fft_truncating_mutant_module;
}

using qemu_test::fail;

namespace
{

DspNode &node_of(void *context)
{
    return *static_cast<DspNode *>(context);
}

void ignore_emit(void *, uint16_t, const int16_t *, uint16_t) {}

// As dsp_node.cpp's: the errors among the VM's reports.
void record_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    DspNode &node = node_of(context);
    if (type == VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS && count == 3)
        node.errors.push_back({ DspError::Kind::array_access, words[0], {} });
    else if (type == VM_REPORT_DIVISION_BY_ZERO && count == 1)
        node.errors.push_back({ DspError::Kind::division_by_zero, words[0], {} });
    else if (type != VM_REPORT_EXECUTION_STATE_CHANGED && type != VM_REPORT_EVENT_EXECUTION_KILLED)
        node.errors.push_back({ DspError::Kind::node_specific,
                                count > 0 ? words[0] : uint16_t(0),
                                "unexpected report" });
}

void record_node_specific(void *context, uint16_t pc, const char *message)
{
    node_of(context).errors.push_back({ DspError::Kind::node_specific, pc, message });
}

const vm_callbacks recording_callbacks = { ignore_emit, record_report, record_node_specific };

constexpr uint16_t init_event = 0xFFFF;
constexpr uint16_t stack_words = 32;

// The index REMOTE_VM_CALL_NATIVE takes for `native`: its place in the
// table, or the mutant's after it.
uint16_t remote_index(const vm_native &native)
{
    if (const std::optional<uint16_t> index = dspic30_test::epuck_index(native))
        return *index;
    if (native.function == nat_dsp_fft_truncating_mutant_module.natives[0].function)
        return vm_native_count(&dspic30_test::epuck_like_table);
    fail("a native the image does not have");
}

} // namespace

DspNode::DspNode(uint16_t variables_size, uint16_t bytecode_words, uint16_t args_size)
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
    vm.memory.args_size = args_size;
    vm.natives = dspic30_test::epuck_like_table;
    vm.callbacks = &recording_callbacks;
    vm.context = this;
    dspic30_test::open_epuck_vm(vm);
}

void DspNode::call(const vm_native &native, const std::vector<int16_t> &popped_words)
{
    if (popped_words.size() != vm_native_stack_words(&native))
        throw std::invalid_argument("wrong argument count for " + description_of(native).name);
    dspic30_test::call_epuck_native(vm, remote_index(native), call_pc, popped_words);
}

void DspNode::put(uint16_t address, const Words &values)
{
    for (size_t i = 0; i < values.size(); ++i)
        variables.at(address + i) = values[i];
}

Words DspNode::get(uint16_t address, uint16_t count) const
{
    if (address + count > variables.size())
        throw std::out_of_range("DspNode::get");
    return Words(variables.begin() + address, variables.begin() + address + count);
}

void DspNode::run_init(const std::vector<uint16_t> &code)
{
    // Event table: one entry, init, whose handler starts at word 3.
    std::vector<uint16_t> image = { 3, init_event, 3 };
    image.insert(image.end(), code.begin(), code.end());
    load_and_run_init(image);
}

void DspNode::load_and_run_init(const std::vector<uint16_t> &image)
{
    if (image.size() > bytecode_.size())
        throw std::invalid_argument("bytecode too long");
    // Uploaded as a host does, so that the verifier sees it; then run.
    vm_set_bytecode(&vm, 0, image.data(), static_cast<uint16_t>(image.size()));
    if (!vm_is_event_active(&vm) || vm.pc != vm_event_address(&vm, init_event))
        throw std::invalid_argument("bytecode does not handle init");
    vm.flags = VM_FLAG_EVENT_ACTIVE;
    vm_run(&vm, 0);
}
