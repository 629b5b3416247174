// The GCC torture corpus on the simulator: every test of
// ../shared/vectors/gcc-torture/manifest.tsv, built into a HEX image by
// tests/dspic30_sim/module.mk, runs from reset until it prints its last line
// on UART1; it passes when that line is the one the manifest expects
// ("EXIT 0"). A failure shows what the program printed and how it ended.

#include "tools/dspic30_sim/intel_hex.hpp"
#include "tools/dspic30_sim/simulator.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace aseba::dspic30
{
namespace
{

// Generous for the corpus (the slowest test needs a few million cycles):
// 10 s of the robot's time, and a wall-clock guard against a runaway.
constexpr uint64_t cycle_limit = 147456000;
constexpr double seconds_limit = 60;
constexpr int failures_shown = 20;

// Tests that pic30-elf-gcc 4.5.1 compiles wrongly at -Os (the corpus' flag),
// found by reading their code; each runs correctly on the simulator when
// built otherwise (-O1 or -O2), except the first, miscompiled at every
// level. They must keep failing: a pass means this list is out of date.
struct KnownMiscompilation {
    const char *name;
    const char *why;
};
constexpr KnownMiscompilation known_miscompilations[] = {
    { "20060110-2",
      "((a + b) << 32) >> 32 on long long: the sign is taken from bit 15 "
      "(asr w2, #15) instead of bit 31" },
    { "20060412-1",
      "while (--q > p): the loop is turned into an upward count (add #4) that "
      "never meets p; -O1 and -O2 count down" },
    { "990208-1",
      "doit() is not inlined at -Os, so both label addresses are one (a quality-"
      "of-implementation test); passes at -O2" },
    { "pr23135",
      "verify() with a zero-size struct argument opens a frame (lnk #0) and returns "
      "without ulnk, to address 0; passes at -O1 and -O2" },
};

const KnownMiscompilation *known_miscompilation(const std::string &name)
{
    for (const auto &k : known_miscompilations)
        if (name == k.name)
            return &k;
    return nullptr;
}

struct Entry {
    std::string name;
    std::string expected;
};

std::vector<Entry> manifest()
{
    std::ifstream in(TORTURE_MANIFEST);
    EXPECT_TRUE(in) << "cannot read " << TORTURE_MANIFEST;
    std::vector<Entry> entries;
    std::string line;
    std::getline(in, line); // the header
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        Entry e;
        std::getline(fields, e.name, '\t');
        std::getline(fields, e.expected, '\t');
        if (!e.name.empty())
            entries.push_back(e);
    }
    return entries;
}

TEST(Torture, EveryTestPrintsItsExpectedLine)
{
    const auto entries = manifest();
    ASSERT_FALSE(entries.empty());
    int passed = 0, failed = 0, miscompiled = 0;
    uint64_t total_cycles = 0;
    for (const Entry &e : entries) {
        std::string output;
        Simulator simulator([&](uint8_t byte) { output += static_cast<char>(byte); });
        std::string problem;
        try {
            simulator.load(
              read_intel_hex_file(std::string(TORTURE_IMAGES) + "/" + e.name + ".hex"));
        } catch (const std::exception &error) {
            problem = error.what();
        }
        RunResult result;
        if (problem.empty()) {
            result = simulator.run(RunLimits{ cycle_limit, seconds_limit, true });
            total_cycles += result.cycles;
            const std::string line = output.substr(0, output.find('\n'));
            if (result.outcome == Outcome::exit_line && line == e.expected)
                ++passed;
            else
                problem = "printed \"" + output + "\", ended by " + outcome_name(result.outcome) +
                          " after " + std::to_string(result.cycles) + " cycles, " +
                          std::to_string(result.trap_count) + " traps";
        }
        const KnownMiscompilation *known = known_miscompilation(e.name);
        if (known && problem.empty())
            ADD_FAILURE() << e.name << " passes although listed as miscompiled: " << known->why;
        if (!problem.empty()) {
            ++failed;
            if (known)
                ++miscompiled;
            else if (failed - miscompiled <= failures_shown)
                ADD_FAILURE() << e.name << ": " << problem;
        }
    }
    std::printf("gcc-torture on dspic30-sim: %d passed, %d failed (%d of them the known pic30-gcc "
                "miscompilations; %zu in the manifest, %llu cycles in all)\n",
                passed,
                failed,
                miscompiled,
                entries.size(),
                static_cast<unsigned long long>(total_cycles));
    EXPECT_EQ(failed, miscompiled) << "failures besides the known miscompilations";
    EXPECT_EQ(passed + miscompiled, static_cast<int>(entries.size()));
}

} // namespace
} // namespace aseba::dspic30
