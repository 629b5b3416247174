// Every compile error of language.md §11.2 at the position the reference
// compiler reports, from data/errors.txt (expectations are the reference's,
// or our documented rewording of them), and the errors of the locals,
// parameters and calls of docs/language.md, from data/language_errors.txt.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "unit_support.hpp"

namespace aseba::unit
{
namespace
{

// The errors of Aseba 1.6's language, then those of docs/language.md's additions.
const char *const DATA_FILES[] = { "tests/compiler_unit/data/errors.txt",
                                   "tests/compiler_unit/data/language_errors.txt" };

struct ErrorCase {
    std::string name;
    std::string source;
    std::string expected; // "error L:C: message" or "error: message"
};

std::vector<ErrorCase> load_cases(const char *path)
{
    std::ifstream file(path);
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

std::vector<ErrorCase> load_cases()
{
    std::vector<ErrorCase> cases;
    for (const char *path : DATA_FILES) {
        std::vector<ErrorCase> more = load_cases(path);
        cases.insert(cases.end(), more.begin(), more.end());
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
    EXPECT_GT(load_cases(DATA_FILES[0]).size(), 50u) << "run the tests from the repository root";
    EXPECT_GT(load_cases(DATA_FILES[1]).size(), 20u);
}

} // namespace
} // namespace aseba::unit
