// libFuzzer target for the dsPIC30F simulator: the input is a random image
// (three bytes per 24-bit program word from PC 0, the first word the reset
// vector), or, when it starts with ':', an Intel HEX file for the loader.
// The chip runs it from reset for a bounded number of cycles with its
// illegal words run as NOPs: whatever the words, the simulator must not
// crash, read out of bounds or hang, and its invariants must hold (the PC
// even and within 23 bits, a run cut by its cycle limit only at that limit).
// Built and run by scripts/fuzz.sh (clang -fsanitize=fuzzer,address,undefined).

#include "tools/dspic30_sim/disassembler.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"
#include "tools/dspic30_sim/simulator.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace
{
constexpr uint64_t cycle_budget = 4000;
constexpr std::size_t bytes_per_word = 3;
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    using namespace aseba::dspic30;
    std::map<uint32_t, uint32_t> words;
    if (size > 0 && data[0] == ':') {
        try {
            words = read_intel_hex(std::string_view(reinterpret_cast<const char *>(data), size));
        } catch (const HexError &) {
            return 0;
        }
    } else {
        for (std::size_t i = 0; i + bytes_per_word <= size; i += bytes_per_word) {
            const uint32_t word =
              data[i] | (data[i + 1] << 8) | (static_cast<uint32_t>(data[i + 2]) << 16);
            words[static_cast<uint32_t>(2 * (i / bytes_per_word))] = word;
            (void)disassemble(static_cast<uint32_t>(2 * (i / bytes_per_word)), word, 0);
        }
    }
    std::string output;
    int input_bytes = 0;
    Simulator simulator([&](uint8_t b) { output += static_cast<char>(b); },
                        [&]() { return input_bytes++ < 64 ? 'U' : -1; });
    try {
        simulator.load(words);
    } catch (const std::invalid_argument &) {
        return 0; // addresses where nothing is implemented
    }
    simulator.cpu().set_stop_on_illegal(false);
    const RunResult result = simulator.run(RunLimits{ cycle_budget, 0, false });
    const Cpu &cpu = simulator.cpu();
    const bool ran_out = result.outcome == Outcome::cycle_limit && result.cycles < cycle_budget;
    if ((cpu.pc() & 1) || cpu.pc() > pc_mask || ran_out) {
        std::fprintf(stderr,
                     "broken invariant: PC %06X after %llu cycles (%s)\n",
                     static_cast<unsigned>(cpu.pc()),
                     static_cast<unsigned long long>(result.cycles),
                     outcome_name(result.outcome).c_str());
        std::abort();
    }
    return 0;
}
