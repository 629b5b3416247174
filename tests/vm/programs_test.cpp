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

// The folder must hold the programs: an empty list would pass silently.
TEST(ProgramFiles, AreFound)
{
    EXPECT_GE(program_files().size(), 20u);
}

} // namespace
