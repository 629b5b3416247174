// Runs every tests/vm/programs/*.asm: each file is a program with the
// actions and expectations of its `#` lines (tests/vm/README.md).

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/vm/program_script.hpp"

namespace
{

const char programs_folder[] = "tests/vm/programs";

std::vector<std::string> program_files()
{
    std::vector<std::string> files;
    for (const auto &entry : std::filesystem::directory_iterator(programs_folder)) {
        if (entry.path().extension() == ".asm")
            files.push_back(entry.path().string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

class ProgramFile : public testing::TestWithParam<std::string>
{
};

TEST_P(ProgramFile, MeetsItsExpectations)
{
    std::ifstream file(GetParam());
    ASSERT_TRUE(file) << "cannot read " << GetParam();
    std::stringstream text;
    text << file.rdbuf();
    ASSERT_NE(text.str().find("# expect"), std::string::npos) << GetParam() << " expects nothing";
    for (const std::string &failure : vm_tests::run_program_script(GetParam(), text.str()))
        ADD_FAILURE() << failure;
}

std::string test_name(const testing::TestParamInfo<std::string> &info)
{
    std::string name = std::filesystem::path(info.param).stem().string();
    std::replace_if(
      name.begin(),
      name.end(),
      [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); },
      '_');
    return name;
}

INSTANTIATE_TEST_SUITE_P(Programs, ProgramFile, testing::ValuesIn(program_files()), test_name);

// A misspelt `# expect` must fail the file, not drop the check: the same
// wrong expectation fails when spelt right and is refused when misspelt.
TEST(ProgramScript, RefusesAnUnknownDirective)
{
    const std::string program =
      "event init start\nstart:\n    SMALL_IMMEDIATE 5\n    STORE 10\n    STOP\n";
    const auto right = vm_tests::run_program_script("right", program + "# expect var[10] = 6\n");
    ASSERT_EQ(right.size(), 1u);
    EXPECT_NE(right[0].find("var[10] is 5, expected 6"), std::string::npos) << right[0];

    const auto misspelt =
      vm_tests::run_program_script("misspelt", program + "# exepct var[10] = 6\n");
    ASSERT_EQ(misspelt.size(), 1u);
    EXPECT_NE(misspelt[0].find("misspelt:6: unknown directive '# exepct'"), std::string::npos)
      << misspelt[0];

    EXPECT_EQ(vm_tests::run_program_script("empty", program + "#\n").size(), 1u)
      << "a bare # is no directive either";
}

// The folder must hold the programs: an empty list would pass silently.
TEST(ProgramFiles, AreFound)
{
    EXPECT_GE(program_files().size(), 20u);
}

} // namespace
