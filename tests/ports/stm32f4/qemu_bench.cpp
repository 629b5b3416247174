// The VM's cost on the emulated STM32F4, in Cortex-M4 instructions per
// bytecode step: bench/vm_workload.aseba (bench-vm's workload) on the
// harness image, QEMU counting instructions (-icount) and the image counting
// the steps and reading its clock (tests/ports/stm32f4/target/harness_server.c).
//
//   bench-qemu [RUNS]   prints the workload's steps, its instructions per
//                       step, and the image's clock per instruction
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
constexpr uint16_t default_runs = 20;

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

        qemu_test::RemoteMachine &machine = qemu_test::RemoteMachine::instance();
        machine.count_instructions = true;
        test_support::VmSizes sizes;
        sizes.bytecode = target.bytecode_size;
        sizes.variables = target.variables_size;
        sizes.stack = target.stack_size;
        test_support::VmHarness harness(sizes);
        harness.load(compiled.bytecode);
        vm_reset(&harness.vm);
        vm_command_run(&harness.vm);
        vm_run(&harness.vm, 0);

        qemu_test::Bytes answer = machine.bench(go_event, runs);
        qemu_test::Reader reader{ answer };
        uint32_t steps = u32(reader);
        uint32_t vm_cycles = u32(reader);
        uint32_t loop_cycles = u32(reader);
        uint32_t loop_instructions = u32(reader);
        double cycles_per_instruction = double(loop_cycles) / loop_instructions;
        double instructions_per_step = double(vm_cycles) / runs / steps / cycles_per_instruction;
        std::printf("steps %u\ninstructions per step %.1f\nclock cycles per instruction %.3f\n",
                    unsigned(steps),
                    instructions_per_step,
                    cycles_per_instruction);
    } catch (const std::exception &failure) {
        std::fprintf(stderr, "bench-qemu: %s\n", failure.what());
        return 1;
    }
    return 0;
}
