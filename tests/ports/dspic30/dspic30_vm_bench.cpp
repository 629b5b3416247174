// The VM's cost on the dsPIC30F6014A, in instruction cycles per bytecode
// step: bench/vm_workload.aseba (bench-vm's and bench-qemu's workload) on the
// harness image, as pic30-elf-gcc -Os builds the application's VM, run on
// the simulator; the image counts the steps and times the runs with
// Timer2/3 (tests/ports/dspic30/target/harness_main.c).
//
//   bench-dspic30-vm [RUNS]   prints the workload's steps, the cycles per
//                             step, the bytecode steps per second that
//                             leaves at the e-puck's 14.7456 MIPS, and the
//                             timer's cycles per instruction on a known loop
//
// scripts/bench.sh runs it from the repository root.

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "tests/ports/stm32f4/remote_link.hpp"
#include "tests/support/vm_harness.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_presets.hpp"

namespace
{

constexpr const char *workload_path = "bench/vm_workload.aseba";
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
    } catch (const std::exception &failure) {
        std::fprintf(stderr, "bench-dspic30-vm: %s\n", failure.what());
        return 1;
    }
    return 0;
}
