// bench-dspic30-sim: the speed of the dsPIC30F simulator on one host core.
// It runs bench/dspic30_workload.c (built with pic30-elf-gcc -Os by
// bench/module.mk) from reset for a number of instruction cycles and prints
// the simulated instructions and cycles per second of host time.
//
// Usage: bench-dspic30-sim [CYCLES]      (default 1,000,000,000)

#include "tools/dspic30_sim/intel_hex.hpp"
#include "tools/dspic30_sim/simulator.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <exception>

namespace
{
// The CPU time of this thread: what one host core spent, whatever else the
// machine runs.
double thread_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}
} // namespace

int main(int argc, char **argv)
{
    using namespace aseba::dspic30;
    constexpr uint64_t default_cycles = 1000000000;
    const uint64_t cycles = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : default_cycles;
    Simulator simulator;
    try {
        simulator.load(read_intel_hex_file(DSPIC30_WORKLOAD));
    } catch (const std::exception &e) {
        std::fprintf(stderr, "bench-dspic30-sim: %s\n", e.what());
        return 2;
    }
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = thread_seconds();
    const RunResult result = simulator.run(RunLimits{ cycles, 0, false });
    const double seconds = thread_seconds() - cpu_start;
    const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const uint64_t instructions = simulator.cpu().instructions();
    if (result.outcome != Outcome::cycle_limit || result.trap_count != 0) {
        std::fprintf(stderr,
                     "bench-dspic30-sim: the workload stopped by %s with %llu traps\n",
                     outcome_name(result.outcome).c_str(),
                     static_cast<unsigned long long>(result.trap_count));
        return 1;
    }
    std::printf("dspic30-sim: %.1f million instructions/s, %.1f million cycles/s on one core "
                "(%llu instructions, %llu cycles in %.2f s of CPU time, %.2f s wall clock; "
                "the chip runs 14.7 million cycles/s)\n",
                instructions / seconds / 1e6,
                result.cycles / seconds / 1e6,
                static_cast<unsigned long long>(instructions),
                static_cast<unsigned long long>(result.cycles),
                seconds,
                wall);
    return 0;
}
