// The VM benchmark: compiles bench/vm_workload.aseba once with our compiler
// for the reference's dummy node, loads the same bytecode into our VM (as
// linked: switch or computed-goto dispatch) or into Debian's reference VM
// (libasebavm), and runs event `go`.
//
//   bench-vm steps VM       counts the steps of one run, one vm_step at a time,
//                           and checks that both VMs end with equal variables
//   bench-vm once VM        one run of the workload; callgrind measures it with
//                           --toggle-collect=vm_run (and vm_run.*, the link-time
//                           optimiser's copies) or AsebaVMRun
//   bench-vm time VM RUNS   wall-clock ns per run of the workload (best of RUNS)
//   bench-vm checksum VM    a checksum of the variables after one run of `go`
//   bench-vm header         the workload's bytecode and memory sizes as a C
//                           header, for bench/avr_workload.c
//
// VM is `ours` or `reference`. scripts/bench.sh runs it from the repo root.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/support/vm_harness.hpp"
#include "tests/vm/reference_node.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_presets.hpp"

namespace
{

constexpr const char *workload_path = "bench/vm_workload.aseba";
constexpr uint16_t go_event = 0; // the only global event of the workload

// The bytecode of the workload, compiled for the dummy node.
std::vector<uint16_t> compile_workload(const aseba::TargetDescription &target)
{
    aseba::ProgramFile program = aseba::read_program_file(workload_path);
    program.definitions.events.push_back({ "go", 0 });
    std::string error_text;
    aseba::CompileResult result = aseba::compile_program_file(program, target, error_text);
    if (!result.ok)
        throw std::runtime_error(error_text);
    return result.bytecode;
}

test_support::VmSizes sizes_of(const aseba::TargetDescription &target)
{
    test_support::VmSizes sizes;
    sizes.bytecode = target.bytecode_size;
    sizes.variables = target.variables_size;
    sizes.stack = target.stack_size;
    return sizes;
}

// One VM with the workload loaded, its init code run, ready for `go`.
class Bench
{
  public:
    virtual ~Bench() = default;
    virtual void start_go() = 0;
    virtual void run_to_end() = 0;      // the measured call: one vm_run
    virtual uint64_t count_steps() = 0; // runs `go` one step at a time
    virtual std::vector<int16_t> variables() = 0;
};

class OurBench : public Bench
{
  public:
    OurBench(const test_support::VmSizes &sizes, const std::vector<uint16_t> &bytecode)
      : harness_(sizes)
      , size_(sizes.variables)
    {
        harness_.load(bytecode);
        vm_reset(&harness_.vm);
        vm_command_run(&harness_.vm);
        vm_run(&harness_.vm, 0);
    }
    void start_go() override
    {
        if (vm_setup_event(&harness_.vm, go_event) == 0)
            throw std::runtime_error("our VM: no handler for go");
    }
    void run_to_end() override
    {
        vm_run(&harness_.vm, 0);
    }
    uint64_t count_steps() override
    {
        start_go();
        uint64_t steps = 0;
        while (vm_is_event_active(&harness_.vm) && vm_step(&harness_.vm))
            steps++;
        return steps;
    }
    std::vector<int16_t> variables() override
    {
        return { harness_.variables(), harness_.variables() + size_ };
    }

  private:
    test_support::VmHarness harness_;
    uint16_t size_;
};

class ReferenceBench : public Bench
{
  public:
    ReferenceBench(const test_support::VmSizes &sizes, const std::vector<uint16_t> &bytecode)
      : node_(sizes)
      , size_(sizes.variables)
    {
        node_.set_bytecode(0, bytecode);
        node_.reset();
        node_.run_command();
        node_.run(0);
    }
    void start_go() override
    {
        if (node_.setup_event(go_event) == 0)
            throw std::runtime_error("reference VM: no handler for go");
    }
    void run_to_end() override
    {
        node_.run(0);
    }
    uint64_t count_steps() override
    {
        constexpr uint16_t one_step = 1; // AsebaVMRun's stepsLimit
        constexpr uint16_t event_active = 1;
        start_go();
        uint64_t steps = 0;
        while ((node_.flags() & event_active) && node_.run(one_step))
            steps++;
        return steps;
    }
    std::vector<int16_t> variables() override
    {
        return { node_.variables(), node_.variables() + size_ };
    }

  private:
    vm_tests::ReferenceNode node_;
    uint16_t size_;
};

std::unique_ptr<Bench> make_bench(const std::string &which)
{
    aseba::TargetDescription target = aseba::dummy_target();
    std::vector<uint16_t> bytecode = compile_workload(target);
    if (which == "ours")
        return std::make_unique<OurBench>(sizes_of(target), bytecode);
    if (which == "reference")
        return std::make_unique<ReferenceBench>(sizes_of(target), bytecode);
    throw std::runtime_error("unknown VM '" + which + "' (ours or reference)");
}

int usage()
{
    std::fprintf(stderr,
                 "usage: bench-vm steps|once|checksum VM  |  bench-vm time VM RUNS  |  "
                 "bench-vm header\n");
    return 2;
}

// The checksum bench/avr_workload.c computes: v(n) = 31 v(n-1) + V[n], 16 bits.
uint16_t checksum_of(const std::vector<int16_t> &variables)
{
    uint16_t checksum = 0;
    for (int16_t value : variables)
        checksum = static_cast<uint16_t>(checksum * 31u + static_cast<uint16_t>(value));
    return checksum;
}

// The header bench/avr_workload.c includes.
int print_header()
{
    aseba::TargetDescription target = aseba::dummy_target();
    std::vector<uint16_t> bytecode = compile_workload(target);
    std::printf("// Generated by `bench-vm header` from %s: do not edit.\n", workload_path);
    std::printf("#define VM_WORKLOAD_BYTECODE_WORDS %u\n", unsigned(target.bytecode_size));
    std::printf("#define VM_WORKLOAD_VARIABLE_WORDS %u\n", unsigned(target.variables_size));
    std::printf("#define VM_WORKLOAD_STACK_WORDS %u\n", unsigned(target.stack_size));
    std::printf("#define VM_WORKLOAD_EVENT %u\n", unsigned(go_event));
    std::printf("static const uint16_t vm_workload[] = {");
    for (size_t i = 0; i < bytecode.size(); i++)
        std::printf("%s0x%04x,", i % 10 == 0 ? "\n    " : " ", bytecode[i]);
    std::printf("\n};\n");
    return 0;
}

} // namespace

int main(int argc, char **argv)
try {
    if (argc == 2 && std::string(argv[1]) == "header")
        return print_header();
    if (argc < 3)
        return usage();
    std::string mode = argv[1];
    std::unique_ptr<Bench> bench = make_bench(argv[2]);

    if (mode == "steps") {
        // The same work on both VMs must leave the same variables and take
        // the same number of steps: the per-step figures compare like with like.
        uint64_t steps = bench->count_steps();
        std::unique_ptr<Bench> other =
          make_bench(std::string(argv[2]) == "ours" ? "reference" : "ours");
        uint64_t other_steps = other->count_steps();
        if (steps != other_steps || bench->variables() != other->variables()) {
            std::fprintf(stderr,
                         "bench-vm: the VMs disagree (%llu vs %llu steps)\n",
                         static_cast<unsigned long long>(steps),
                         static_cast<unsigned long long>(other_steps));
            return 1;
        }
        std::printf("%llu\n", static_cast<unsigned long long>(steps));
        return 0;
    }
    if (mode == "once") {
        bench->start_go();
        bench->run_to_end();
        return 0;
    }
    if (mode == "checksum") {
        bench->start_go();
        bench->run_to_end();
        std::printf("%u\n", unsigned(checksum_of(bench->variables())));
        return 0;
    }
    if (mode == "time" && argc == 4) {
        int runs = std::max(1, std::atoi(argv[3]));
        double best_ns = 1e300;
        for (int run = 0; run < runs; run++) {
            bench->start_go();
            auto begin = std::chrono::steady_clock::now();
            bench->run_to_end();
            auto end = std::chrono::steady_clock::now();
            best_ns =
              std::min(best_ns, std::chrono::duration<double, std::nano>(end - begin).count());
        }
        std::printf("%.0f\n", best_ns);
        return 0;
    }
    return usage();
} catch (const std::exception &error) {
    std::fprintf(stderr, "bench-vm: %s\n", error.what());
    return 1;
}
