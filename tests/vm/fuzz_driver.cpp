#include "tests/vm/fuzz_driver.hpp"

#include <algorithm>
#include <memory>
#include <sstream>

#include "tests/support/native_table.hpp"

namespace vm_tests
{

namespace
{

using test_support::VmHarness;
using test_support::VmMessage;

constexpr size_t MAX_COMMANDS = 32;
constexpr uint16_t FLAG_BITS = VM_FLAG_EVENT_ACTIVE | VM_FLAG_STEP_BY_STEP | VM_FLAG_EVENT_RUNNING;

// The harness natives without test.yield: a native that clears
// EVENT_RUNNING would make vm_run and repeated vm_step differ by design.
const vm_native_table &fuzz_natives()
{
    // The harness's natives are one module: its first records are contiguous.
    static const test_support::OneModuleTable table(
      vm_native_at(&test_support::test_native_table(), 0), test_support::NATIVE_YIELD);
    return table;
}

// Reads the command stream; past its end every byte is 0.
class CommandReader
{
  public:
    explicit CommandReader(const std::vector<uint8_t> &bytes)
      : bytes_(bytes)
    {
    }
    bool done() const
    {
        return position_ >= bytes_.size();
    }
    uint8_t byte()
    {
        return position_ < bytes_.size() ? bytes_[position_++] : 0;
    }
    uint16_t word()
    {
        uint16_t low = byte();
        return static_cast<uint16_t>(low | (byte() << 8));
    }

  private:
    const std::vector<uint8_t> &bytes_;
    size_t position_ = 0;
};

// A second VM in the same state as `original`, for vm_run / vm_step checks.
std::unique_ptr<VmHarness> clone(VmHarness &original)
{
    auto copy = std::make_unique<VmHarness>(original.sizes(), original.vm.node_id, fuzz_natives());
    const test_support::VmSizes &sizes = original.sizes();
    std::copy_n(original.bytecode(), sizes.bytecode, copy->bytecode());
    std::copy_n(original.variables(), sizes.variables, copy->variables());
    std::copy_n(original.stack(), sizes.stack, copy->stack());
    copy->vm.pc = original.vm.pc;
    copy->vm.sp = original.vm.sp;
    copy->vm.flags = original.vm.flags;
    copy->vm.breakpoint_count = original.vm.breakpoint_count;
    std::copy_n(original.vm.breakpoints, VM_MAX_BREAKPOINTS, copy->vm.breakpoints);
    copy->vm.random_state = original.vm.random_state;
    // The copied bytecode is the one the original verified.
    copy->vm.rejection = original.vm.rejection;
    copy->vm.rejection_pc = original.vm.rejection_pc;
    return copy;
}

// The texts of faults that only the verifier finds; the run loop never
// checks them (vm/vm.c).
bool is_verifier_fault(const std::string &text)
{
    for (const char *fault : { "out of bytecode bounds",
                               "unknown bytecode",
                               "unknown operator",
                               "unknown native function",
                               "emitted event too large",
                               "invalid jump" })
        if (text == fault)
            return true;
    return false;
}

std::string same_state(VmHarness &a, VmHarness &b, size_t a_log_from)
{
    const test_support::VmSizes &sizes = a.sizes();
    if (!std::equal(a.bytecode(), a.bytecode() + sizes.bytecode, b.bytecode()))
        return "bytecode differs";
    if (!std::equal(a.variables(), a.variables() + sizes.variables, b.variables()))
        return "variables differ";
    if (a.vm.sp != b.vm.sp || a.vm.pc != b.vm.pc)
        return "pc or sp differ";
    if ((a.vm.flags & ~VM_FLAG_EVENT_RUNNING) != (b.vm.flags & ~VM_FLAG_EVENT_RUNNING))
        return "flags differ";
    if (!std::equal(
          a.log.begin() + static_cast<long>(a_log_from), a.log.end(), b.log.begin(), b.log.end()))
        return "messages differ";
    return "";
}

class FuzzRun
{
  public:
    FuzzRun(const FuzzCase &fuzz_case, FuzzStats *stats)
      : case_(fuzz_case)
      , harness_(fuzz_case.sizes, 1, fuzz_natives())
      , stats_(stats)
    {
    }
    std::string run();

  private:
    std::string check(const std::string &command, size_t log_from, bool after_run);
    std::string run_with_budget(uint16_t budget);

    const FuzzCase &case_;
    VmHarness harness_;
    unsigned run_count_ = 0;
    FuzzStats *stats_;
};

std::string FuzzRun::check(const std::string &command, size_t log_from, bool after_run)
{
    const vm_state &vm = harness_.vm;
    std::ostringstream problem;
    if (!harness_.guards_intact())
        problem << "memory outside the VM's arrays was written";
    else if (vm.flags & ~FLAG_BITS)
        problem << "unknown flags " << vm.flags;
    else if (vm.sp < -1 || vm.sp >= static_cast<int32_t>(harness_.sizes().stack))
        problem << "sp " << vm.sp << " outside the stack";
    else if (vm.breakpoint_count > VM_MAX_BREAKPOINTS)
        problem << "breakpoint count " << vm.breakpoint_count;
    else if (after_run && (vm.flags & VM_FLAG_EVENT_RUNNING) && !(vm.flags & VM_FLAG_STEP_BY_STEP))
        problem << "EVENT_RUNNING left set by a run that was not stopped by a breakpoint";
    for (uint16_t i = 0; problem.str().empty() && i < vm.breakpoint_count; i++) {
        if (vm.breakpoints[i] >= harness_.sizes().bytecode)
            problem << "breakpoint " << vm.breakpoints[i] << " beyond the bytecode";
    }
    bool stopped_by_error = false;
    for (size_t i = log_from; problem.str().empty() && i < harness_.log.size(); i++) {
        const VmMessage &message = harness_.log[i];
        if (stats_)
            stats_->messages[message.kind]++;
        switch (message.kind) {
        case VmMessage::EMIT:
            if (message.payload.size() > VM_MAX_EVENT_WORDS || message.pc > 0x0FFF)
                problem << "bad emit: " << describe(message);
            break;
        case VmMessage::ARRAY_ACCESS:
            if (message.index < message.size)
                problem << "array error for an index inside the array: " << describe(message);
            if (message.pc != vm.pc)
                problem << "pc moved after an array error";
            stopped_by_error = true;
            break;
        case VmMessage::DIVISION_BY_ZERO:
        case VmMessage::NODE_ERROR: stopped_by_error = true; break;
        default: break;
        }
        if (message.kind == VmMessage::NODE_ERROR && message.text.size() > VM_NODE_ERROR_LENGTH)
            problem << "node error text too long";
        // Faults the verifier rules out are reported only for a program it
        // refused (by RUN and STEP): a run that meets one ran unverified code.
        if (message.kind == VmMessage::NODE_ERROR && is_verifier_fault(message.text) &&
            (vm.rejection == nullptr || message.text != vm.rejection ||
             message.pc != vm.rejection_pc))
            problem << "a run reported what the verifier rules out: " << describe(message);
    }
    if (problem.str().empty() && stopped_by_error && after_run && vm.flags != VM_FLAG_STEP_BY_STEP)
        problem << "flags " << vm.flags << " after an error";
    if (problem.str().empty())
        return "";
    return "after " + command + ": " + problem.str();
}

// vm_run with a budget must do what as many vm_step calls do, then stop.
std::string FuzzRun::run_with_budget(uint16_t budget)
{
    size_t log_from = harness_.log.size();
    bool compare = harness_.vm.breakpoint_count == 0 && run_count_++ % 4 == 0;
    std::unique_ptr<VmHarness> stepped;
    if (compare)
        stepped = clone(harness_);
    bool can_run = vm_is_event_active(&harness_.vm) && !(harness_.vm.flags & VM_FLAG_STEP_BY_STEP);
    bool ran = vm_run(&harness_.vm, budget);
    if (stats_) {
        stats_->runs++;
        stats_->run_step_comparisons += compare && can_run;
    }
    if (ran != can_run)
        return "vm_run returned " + std::to_string(ran);
    if (compare && can_run) {
        for (uint16_t i = 0; i < budget && vm_is_event_active(&stepped->vm) &&
                             !(stepped->vm.flags & VM_FLAG_STEP_BY_STEP);
             i++)
            vm_step(&stepped->vm);
        std::string difference = same_state(harness_, *stepped, log_from);
        if (!difference.empty())
            return "vm_run(" + std::to_string(budget) + ") and as many vm_step: " + difference;
    }
    // A call that ran nothing leaves the flags as they were: EVENT_RUNNING may
    // still be set from a breakpoint stop followed by steps, as upstream.
    return check("run " + std::to_string(budget), log_from, ran);
}

std::string FuzzRun::run()
{
    vm_state *vm = &harness_.vm;
    vm_set_bytecode(vm, 0, case_.image.data(), static_cast<uint16_t>(case_.image.size()));
    std::string problem = check("SET_BYTECODE", 0, false);
    if (!problem.empty())
        return problem;
    if (stats_) {
        stats_->uploads++;
        stats_->accepted_uploads += vm->rejection == nullptr && vm_is_event_active(vm);
    }
    vm_command_run(vm);
    if (!(problem = run_with_budget(FUZZ_MAX_BUDGET)).empty())
        return problem;

    CommandReader reader(case_.commands);
    for (size_t n = 0; n < MAX_COMMANDS && !reader.done(); n++) {
        size_t log_from = harness_.log.size();
        uint8_t command = reader.byte();
        std::string name;
        switch (command % 14) {
        case 0:
            problem = run_with_budget(static_cast<uint16_t>(1 + reader.byte() % FUZZ_MAX_BUDGET));
            break;
        case 1: {
            uint16_t event = reader.byte() % 4 == 0 ? reader.word() : reader.byte() % 3;
            uint16_t source = reader.word();
            std::vector<int16_t> payload(reader.byte() + (reader.byte() % 2 ? 100 : 0));
            for (int16_t &word : payload)
                word = static_cast<int16_t>(reader.word());
            vm_receive_event(
              vm, event, source, payload.data(), static_cast<uint16_t>(payload.size()));
            name = "receive";
            break;
        }
        case 2: {
            static const uint16_t events[] = { 0xFFFF, 0xFFFE, 0, 1 };
            uint8_t which = reader.byte();
            vm_setup_event(vm, which < 200 ? events[which % 4] : reader.word());
            name = "setup event";
            break;
        }
        case 3:
            vm_command_run(vm);
            name = "RUN";
            break;
        case 4:
            vm_command_pause(vm);
            name = "PAUSE";
            break;
        case 5:
            vm_command_step(vm);
            name = "STEP";
            break;
        case 6:
            vm_command_stop(vm);
            name = "STOP";
            break;
        case 7:
            vm_reset(vm);
            name = "RESET";
            break;
        case 8:
            vm_report_state(vm);
            name = "GET_EXECUTION_STATE";
            break;
        case 9: {
            uint16_t pc = reader.byte() < 230 ? reader.byte() : reader.word();
            vm_breakpoint_set(vm, pc);
            name = "BREAKPOINT_SET";
            break;
        }
        case 10:
            vm_breakpoint_clear(vm,
                                vm->breakpoint_count > 0
                                  ? vm->breakpoints[reader.byte() % vm->breakpoint_count]
                                  : reader.word());
            name = "BREAKPOINT_CLEAR";
            break;
        case 11:
            vm_breakpoint_clear_all(vm);
            name = "BREAKPOINT_CLEAR_ALL";
            break;
        case 12: {
            uint16_t start = reader.byte() < 200 ? reader.byte() : reader.word();
            std::vector<uint16_t> words(reader.byte() % 8);
            for (uint16_t &word : words)
                word = reader.word();
            vm_set_bytecode(vm, start, words.data(), static_cast<uint16_t>(words.size()));
            name = "SET_BYTECODE part";
            break;
        }
        default:
            vm_step(vm);
            name = "vm_step";
            break;
        }
        if (problem.empty() && !name.empty())
            problem = check(name, log_from, false);
        if (!problem.empty())
            return problem;
    }
    return "";
}

} // namespace

std::string run_fuzz_case(const FuzzCase &fuzz_case, FuzzStats *stats)
{
    return FuzzRun(fuzz_case, stats).run();
}

FuzzCase fuzz_case_from_bytes(const uint8_t *data, size_t size)
{
    static const uint16_t bytecode_sizes[] = { 0, 1, 2, 3, 5, 8, 16, 32, 64, 256 };
    static const uint16_t variable_sizes[] = { 0, 1, 2, 3, 8, 34, 64, 300 };
    static const uint16_t stack_sizes[] = { 0, 1, 2, 4, 8, 32 };
    static const uint16_t args_sizes[] = { 0, 1, 8, 32, 300 };
    FuzzCase fuzz_case;
    auto byte = [&](size_t i) -> uint8_t { return i < size ? data[i] : 0; };
    fuzz_case.sizes.bytecode = bytecode_sizes[byte(0) % std::size(bytecode_sizes)];
    fuzz_case.sizes.variables = variable_sizes[byte(1) % std::size(variable_sizes)];
    fuzz_case.sizes.stack = stack_sizes[byte(2) % std::size(stack_sizes)];
    fuzz_case.sizes.args = args_sizes[byte(3) % std::size(args_sizes)];
    size_t image_words = byte(4);
    size_t position = 5;
    for (size_t i = 0; i < image_words && position + 1 < size; i++, position += 2)
        fuzz_case.image.push_back(
          static_cast<uint16_t>(data[position] | (data[position + 1] << 8)));
    if (position < size)
        fuzz_case.commands.assign(data + position, data + size);
    return fuzz_case;
}

} // namespace vm_tests
