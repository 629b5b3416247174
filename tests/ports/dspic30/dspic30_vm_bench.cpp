// The VM's cost on the dsPIC30F6014A, in instruction cycles per bytecode
// step: bench/vm_workload.aseba (bench-vm's and bench-qemu's workload) on the
// harness image, as pic30-elf-gcc -Os builds the application's VM, run on
// the simulator; the image counts the steps and times the runs with
// Timer2/3 (tests/ports/dspic30/target/harness_main.c). Then the paper's
// controller (examples/paper-annex.aesl, for the e-puck, with the e-puck's
// natives) on its ir_sensors event, every sensor at 0.
//
//   bench-dspic30-vm [RUNS]   prints the workload's steps, the cycles per
//                             step, the bytecode steps per second that
//                             leaves at the e-puck's 14.7456 MIPS, and the
//                             timer's cycles per instruction on a known loop;
//                             then the paper controller's steps and cycles
//                             per step
//
// scripts/bench.sh runs it from the repository root.

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tests/ports/stm32f4/remote_link.hpp"
#include "tests/support/vm_harness.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_presets.hpp"

namespace
{

constexpr const char *workload_path = "bench/vm_workload.aseba";
constexpr const char *paper_annex_path = "examples/paper-annex.aesl";
constexpr const char *paper_annex_event = "ir_sensors";
// The first local event's id (init is 0xFFFF; bytecode.md).
constexpr uint16_t first_local_event = 0xFFFE;
constexpr uint16_t go_event = 0;
constexpr uint16_t default_runs = 5;
// The e-puck's instruction clock: 7.3728 MHz crystal, PLL x8, 4 clocks per
// instruction cycle (boards/epuck_dspic30/epuck_dspic30_config.h).
constexpr double epuck_cycles_per_second = 14745600.0;

uint32_t u32(qemu_test::Reader &reader)
{
    uint32_t low = reader.u16();
    return low | uint32_t(reader.u16()) << 16;
}

// One REMOTE_BENCH of `event`: steps, and cycles per step.
std::pair<uint32_t, double> bench_event(uint16_t event, uint16_t runs)
{
    qemu_test::Bytes answer = qemu_test::RemoteMachine::instance().bench(event, runs);
    qemu_test::Reader reader{ answer };
    uint32_t steps = u32(reader);
    uint32_t vm_cycles = u32(reader);
    if (steps == 0 || runs == 0)
        throw std::runtime_error("the event ran no step");
    return { steps, double(vm_cycles) / runs / steps };
}

// The paper's controller on a bare VM of the image with the e-puck's
// natives and memory (its bytecode area is the image's largest, 512 words).
void bench_paper_annex(uint16_t runs)
{
    aseba::TargetDescription target = aseba::epuck_target();
    aseba::ProgramFile program = aseba::read_program_file(paper_annex_path);
    std::string error;
    aseba::CompileResult compiled = aseba::compile_program_file(program, target, error);
    if (!compiled.ok)
        throw std::runtime_error(error);
    uint16_t event = first_local_event;
    while (event > first_local_event - target.local_events.size() &&
           target.local_events[first_local_event - event].name != paper_annex_event)
        --event;

    constexpr uint16_t bytecode_words = 512;
    if (compiled.bytecode.size() > bytecode_words)
        throw std::runtime_error("the paper's controller does not fit the image");
    static std::vector<uint16_t> bytecode(bytecode_words);
    static std::vector<int16_t> variables(target.variables_size);
    static std::vector<int16_t> stack(target.stack_size);
    static vm_state vm;
    vm.memory.bytecode = bytecode.data();
    vm.memory.bytecode_size = bytecode_words;
    vm.memory.variables = variables.data();
    vm.memory.variables_size = target.variables_size;
    vm.memory.stack = stack.data();
    vm.memory.stack_size = target.stack_size;
    vm.memory.args_size = 0;
    static const vm_callbacks quiet = { [](void *, uint16_t, const int16_t *, uint16_t) {},
                                        [](void *, uint16_t, const uint16_t *, uint16_t) {},
                                        [](void *, uint16_t, const char *) {} };
    vm.callbacks = &quiet;
    qemu_test::Bytes answer =
      qemu_test::RemoteMachine::instance().open(REMOTE_OPEN_VM, REMOTE_NATIVES_EPUCK, &vm, 1);
    qemu_test::Reader reader{ answer };
    qemu_test::RemoteMachine::instance().take_changes(reader);
    vm_set_bytecode(&vm, 0, compiled.bytecode.data(), uint16_t(compiled.bytecode.size()));
    vm_reset(&vm);
    vm_command_run(&vm);
    vm_run(&vm, 0); // init

    auto [steps, cycles_per_step] = bench_event(event, runs);
    std::printf(
      "paper annex steps %u\npaper annex cycles per step %.1f\n", unsigned(steps), cycles_per_step);
}

} // namespace

int main(int argc, char **argv)
{
    uint16_t runs = argc > 1 ? uint16_t(std::atoi(argv[1])) : default_runs;
    try {
        aseba::TargetDescription target = aseba::dummy_target();
        aseba::ProgramFile program = aseba::read_program_file(workload_path);
        program.definitions.events.push_back({ "go", 0 });
        std::string error;
        aseba::CompileResult compiled = aseba::compile_program_file(program, target, error);
        if (!compiled.ok)
            throw std::runtime_error(error);

        test_support::VmSizes sizes;
        sizes.bytecode = target.bytecode_size;
        sizes.variables = target.variables_size;
        sizes.stack = target.stack_size;
        test_support::VmHarness harness(sizes);
        harness.load(compiled.bytecode);
        vm_reset(&harness.vm);
        vm_command_run(&harness.vm);
        vm_run(&harness.vm, 0);

        qemu_test::Bytes answer = qemu_test::RemoteMachine::instance().bench(go_event, runs);
        qemu_test::Reader reader{ answer };
        uint32_t steps = u32(reader);
        uint32_t vm_cycles = u32(reader);
        uint32_t loop_cycles = u32(reader);
        uint32_t loop_instructions = u32(reader);
        if (steps == 0 || runs == 0)
            throw std::runtime_error("the workload ran no step");
        double cycles_per_step = double(vm_cycles) / runs / steps;
        std::printf("steps %u\ncycles per step %.1f\nsteps per second at 14.7456 MIPS %.0f\n"
                    "timer cycles per instruction %.3f\n",
                    unsigned(steps),
                    cycles_per_step,
                    epuck_cycles_per_second / cycles_per_step,
                    double(loop_cycles) / loop_instructions);
        bench_paper_annex(runs);
    } catch (const std::exception &failure) {
        std::fprintf(stderr, "bench-dspic30-vm: %s\n", failure.what());
        return 1;
    }
    return 0;
}
