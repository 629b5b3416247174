// What the command-line tools get from the compiler library when a user
// tries things: asebac run on the e-puck, program files that are folders or
// endless, errors that would put control characters on the terminal.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "tools/asebac/run.hpp"
#include "tools/compiler/error_format.hpp"
#include "tools/compiler/program_file.hpp"
#include "unit_support.hpp"

namespace aseba::unit
{
namespace
{

constexpr unsigned long STEP_BUDGET = 10000;

// The issue: `asebac run` failed for every program on the default target,
// whose DSP natives had no host implementation.
TEST(AsebacRun, RunsOnTheEpuckWithEveryNative)
{
    const TargetDescription target = epuck_target();
    CompileResult compiled = compile("var x = 3\n", target, {});
    ASSERT_TRUE(compiled.ok) << compiled.error.message;
    std::string report, error;
    ASSERT_TRUE(run_program(compiled, target, {}, {}, STEP_BUDGET, report, error)) << error;
    EXPECT_NE(report.find("\"x\": 3"), std::string::npos) << report;
}

TEST(AsebacRun, RunsLocalsAndSubroutinesOnTheEpuck)
{
    const TargetDescription target = epuck_target();
    CompileResult compiled = compile("var x\nlocal a = 20\nx = half(a) + 1\n"
                                     "sub half(v)\n    return v / 2\n",
                                     target,
                                     {});
    ASSERT_TRUE(compiled.ok) << compiled.error.message;
    RunOutcome outcome;
    std::string error;
    ASSERT_TRUE(execute_program(compiled, target, {}, {}, STEP_BUDGET, outcome, error)) << error;
    ASSERT_EQ(compiled.variables.back().name, "x");
    EXPECT_EQ(outcome.memory[compiled.variables.back().address], 11);
}

TEST(ProgramFile, FolderIsAnError)
{
    try {
        read_program_file(std::filesystem::temp_directory_path().string());
        FAIL() << "a folder was read as a program";
    } catch (const std::runtime_error &error) {
        EXPECT_NE(std::string(error.what()).find("is a folder"), std::string::npos) << error.what();
    }
}

TEST(ProgramFile, EndlessFileIsAnError)
{
    try {
        read_program_file("/dev/zero");
        FAIL() << "/dev/zero was read";
    } catch (const std::runtime_error &error) {
        EXPECT_NE(std::string(error.what()).find("larger than 4 MiB"), std::string::npos)
          << error.what();
    }
}

TEST(ProgramFile, ProgramsLargerThanTheCompilerTakesAreErrors)
{
    std::string source = "var x\n";
    while (source.size() <= MAX_SOURCE_BYTES)
        source += "x = 1 # padding\n";
    CompileResult result = compile_for_dummy(source);
    ASSERT_FALSE(result.ok);
    EXPECT_EQ(result.error.message.rfind("This program is ", 0), 0u) << result.error.message;
}

// Control characters of a bad line must not reach the terminal; each shows
// as one mark so that the caret still points at the right column.
TEST(ErrorFormat, ControlCharactersAreShownAsMarks)
{
    const std::string source = "var x\nx = \x01\x1b[31m 3\n";
    CompileResult result = compile_for_dummy(source);
    ASSERT_FALSE(result.ok);
    std::string shown = format_error("x.aseba", source, result.error);
    EXPECT_EQ(shown.find('\x1b'), std::string::npos) << shown;
    EXPECT_EQ(shown.find('\x01'), std::string::npos) << shown;
    EXPECT_NE(shown.find("x = \xef\xbf\xbd\xef\xbf\xbd[31m 3"), std::string::npos) << shown;
    EXPECT_NE(shown.find("\n      ^\n"), std::string::npos) << shown;
}

} // namespace
} // namespace aseba::unit
