// Every compile error of language.md §11.2 at the position the reference
// compiler reports, from data/errors.txt (expectations are the reference's).

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "unit_support.hpp"

namespace aseba::unit
{
namespace
{

const char *const DATA_FILE = "tests/compiler_unit/data/errors.txt";

struct ErrorCase {
    std::string name;
    std::string source;
    std::string expected; // "error L:C: message" or "error: message"
};

std::vector<ErrorCase> load_cases()
{
    std::ifstream file(DATA_FILE);
    std::vector<ErrorCase> cases;
    std::string line;
    while (std::getline(file, line)) {
        if (line.rfind("=== ", 0) == 0) {
            cases.push_back({ line.substr(4), "", "" });
        } else if (line.rfind("--- ", 0) == 0 && !cases.empty()) {
            cases.back().expected = line.substr(4);
        } else if (!cases.empty() && cases.back().expected.empty()) {
            cases.back().source += line + "\n";
        }
    }
    return cases;
}

std::string verdict(const CompileResult &result)
{
    if (result.ok)
        return "ok";
    if (!result.error.has_position)
        return "error: " + result.error.message;
    return "error " + std::to_string(result.error.position.line) + ":" +
           std::to_string(result.error.position.column) + ": " + result.error.message;
}

class CompileErrors : public ::testing::TestWithParam<ErrorCase>
{
};

TEST_P(CompileErrors, MatchReference)
{
    const ErrorCase &error_case = GetParam();
    CompileResult result = compile_for_dummy(
      error_case.source, { { "e0", 0 }, { "e1", 1 }, { "e3", 3 } }, { { "C", 5 } });
    EXPECT_EQ(verdict(result), error_case.expected) << error_case.source;
}

INSTANTIATE_TEST_SUITE_P(Reference,
                         CompileErrors,
                         ::testing::ValuesIn(load_cases()),
                         [](const auto &test_info) { return test_info.param.name; });

TEST(CompileErrors, DataFileIsThere)
{
    EXPECT_GT(load_cases().size(), 50u) << "run the tests from the repository root";
}

} // namespace
} // namespace aseba::unit
