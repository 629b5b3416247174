// Differential tests of the simulator: the C programs of
// tests/dspic30_sim/differential, compiled by pic30-elf-gcc -Os and run on
// the simulator, against the same programs compiled for the host (gcc, with
// UBSan so that a report cannot rest on undefined behaviour). Both reports
// must be identical, line by line.

#include "tests/dspic30_sim/pic30_toolchain.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"
#include "tools/dspic30_sim/simulator.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace aseba::dspic30
{
namespace
{

constexpr uint64_t cycle_limit = 500000000;
constexpr double seconds_limit = 120;
constexpr const char *programs[] = { "arithmetic", "control", "constants" };

std::vector<std::string> lines_of(const std::string &text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line))
        lines.push_back(line);
    return lines;
}

class Differential : public testing::TestWithParam<const char *>
{
};

TEST_P(Differential, SimulatedDspicReportsWhatTheHostReports)
{
    const std::string base = std::string(DIFFERENTIAL_OUT) + "/" + GetParam();
    const auto host = lines_of(test::run_command(base + ".host"));
    std::string output;
    Simulator simulator([&](uint8_t byte) { output += static_cast<char>(byte); });
    simulator.load(read_intel_hex_file(base + ".hex"));
    const RunResult result = simulator.run(RunLimits{ cycle_limit, seconds_limit, true });
    EXPECT_EQ(result.outcome, Outcome::exit_line) << outcome_name(result.outcome);
    EXPECT_EQ(result.trap_count, 0u);
    const auto dspic = lines_of(output);
    ASSERT_GE(host.size(), 2u) << "the host program reported nothing";
    EXPECT_EQ(dspic, host);
    std::printf("%s: %zu reports agree, %llu cycles on the dsPIC\n",
                GetParam(),
                host.size() - 1,
                static_cast<unsigned long long>(result.cycles));
}

INSTANTIATE_TEST_SUITE_P(Programs, Differential, testing::ValuesIn(programs));

} // namespace
} // namespace aseba::dspic30
