// The language of docs/language.md (locals, parameters, return values,
// calls in expressions) compiled and run on our VM, from data/language.txt:
// each program with the memory and events it must leave.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "tools/asebac/run.hpp"
#include "unit_support.hpp"

namespace aseba::unit
{
namespace
{

const char *const DATA_FILE = "tests/compiler_unit/data/language.txt";
constexpr unsigned long STEP_BUDGET = 10000;

struct LanguageCase {
    std::string name;
    std::string source;
    std::vector<EventToSend> events;
    std::vector<std::pair<std::string, std::vector<int16_t>>> expected; // global -> words
    std::vector<std::string> emitted;                                   // as the run reports them
    int locals_words = -1;                                              // -1: not checked
};

std::vector<int16_t> numbers(std::istream &words)
{
    std::vector<int16_t> values;
    long value = 0;
    while (words >> value)
        values.push_back(static_cast<int16_t>(value));
    return values;
}

std::string emitted_text(const std::string &event, const std::vector<int16_t> &arguments)
{
    std::string text = "{\"event\": \"" + event + "\", \"args\": [";
    for (size_t i = 0; i < arguments.size(); ++i)
        text += (i ? ", " : "") + std::to_string(arguments[i]);
    return text + "]}";
}

void read_directive(LanguageCase &language_case, const std::string &directive)
{
    std::istringstream words(directive);
    std::string verb, name, equal;
    words >> verb >> name;
    if (verb == "send") {
        language_case.events.push_back({ name, numbers(words) });
    } else if (verb == "expect") {
        words >> equal;
        language_case.expected.push_back({ name, numbers(words) });
    } else if (verb == "emitted") {
        language_case.emitted.push_back(emitted_text(name, numbers(words)));
    } else if (verb == "locals") {
        language_case.locals_words = std::stoi(name);
    } else {
        ADD_FAILURE() << language_case.name << ": unknown directive " << directive;
    }
}

std::vector<LanguageCase> load_cases()
{
    std::ifstream file(DATA_FILE);
    std::vector<LanguageCase> cases;
    std::string line;
    bool in_source = false;
    while (std::getline(file, line)) {
        if (line.rfind("=== ", 0) == 0) {
            cases.push_back({});
            cases.back().name = line.substr(4);
            in_source = true;
        } else if (line.rfind("--- ", 0) == 0 && !cases.empty()) {
            in_source = false;
            read_directive(cases.back(), line.substr(4));
        } else if (in_source) {
            cases.back().source += line + "\n";
        }
    }
    return cases;
}

CommonDefinitions definitions()
{
    CommonDefinitions made;
    made.events = { { "go", 0 }, { "ping", 1 }, { "pair", 2 } };
    return made;
}

class Language : public ::testing::TestWithParam<LanguageCase>
{
};

TEST_P(Language, RunsAsDocumented)
{
    const LanguageCase &language_case = GetParam();
    const TargetDescription target = dummy_target();
    CompileResult compiled = compile(language_case.source, target, definitions());
    ASSERT_TRUE(compiled.ok) << compiled.error.position.line << ":"
                             << compiled.error.position.column << ": " << compiled.error.message
                             << "\n"
                             << language_case.source;
    RunOutcome outcome;
    std::string error;
    ASSERT_TRUE(execute_program(
      compiled, target, definitions(), language_case.events, STEP_BUDGET, outcome, error))
      << error;
    EXPECT_TRUE(outcome.errors.empty()) << outcome.errors.front();
    EXPECT_TRUE(outcome.unfinished.empty());
    for (const auto &[name, words] : language_case.expected) {
        const VariableInfo *found = nullptr;
        for (const VariableInfo &variable : compiled.variables)
            if (variable.name == name)
                found = &variable;
        ASSERT_NE(found, nullptr) << "no global " << name;
        std::vector<int16_t> actual(outcome.memory.begin() + found->address,
                                    outcome.memory.begin() + found->address + found->size);
        EXPECT_EQ(actual, words) << name;
    }
    EXPECT_EQ(outcome.emitted, language_case.emitted);
    if (language_case.locals_words >= 0) {
        EXPECT_EQ(compiled.locals_words, language_case.locals_words);
    }
}

INSTANTIATE_TEST_SUITE_P(Programs,
                         Language,
                         ::testing::ValuesIn(load_cases()),
                         [](const auto &test_info) { return test_info.param.name; });

TEST(Language, DataFileIsThere)
{
    EXPECT_GT(load_cases().size(), 20u) << "run the tests from the repository root";
}

} // namespace
} // namespace aseba::unit
