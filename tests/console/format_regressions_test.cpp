// Inputs the libFuzzer target of the file formats once failed on
// (tests/fuzz/regressions/formats/, scripts/fuzz.sh formats): each is read
// as a project and as a target description without an exception escaping,
// and gives a clear error when it is no valid one.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tools/compiler/aesl.hpp"
#include "tools/compiler/target_json.hpp"

TEST(FormatRegressions, EveryKeptInputReadsWithoutAnEscapingException)
{
    const std::filesystem::path folder = "tests/fuzz/regressions/formats";
    size_t inputs = 0;
    for (const auto &entry : std::filesystem::directory_iterator(folder)) {
        std::ifstream file(entry.path(), std::ios::binary);
        std::ostringstream text;
        text << file.rdbuf();
        SCOPED_TRACE(entry.path().string());
        aseba::AeslReadResult project;
        aseba::TargetReadResult target;
        EXPECT_NO_THROW(project = aseba::read_aesl(text.str()));
        EXPECT_NO_THROW(target = aseba::read_target_json(text.str()));
        if (!target.ok) {
            EXPECT_FALSE(target.error.empty());
        }
        inputs++;
    }
    EXPECT_GT(inputs, 0u) << "no input in " << folder;
}

// A number beyond every integer type is an error of the file, like any
// other value out of range (nlohmann-json throws out_of_range for it).
TEST(FormatRegressions, ANumberBeyondAnyIntegerIsAnError)
{
    aseba::TargetReadResult read = aseba::read_target_json(
      R"({"name": "x", "bytecode_size": 1e99999, "variables_size": 1, "stack_size": 1})");
    EXPECT_FALSE(read.ok);
    EXPECT_NE(read.error.find("number overflow"), std::string::npos) << read.error;
}
