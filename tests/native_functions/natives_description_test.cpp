// The descriptions of the standard natives: names, documentation strings and
// parameters against the table of language.md §13.1 (read from the shared
// specification) and against Debian's reference descriptions; and the
// stack contract of bytecode.md §9.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "our_node.hpp"
#include "tests/support/native_table.hpp"

extern "C" {
#include <aseba/vm/natives.h>

#include "nat_dsp.h"
#include "nat_words.h"
}

namespace
{

struct Parameter {
    std::string name;
    int size;
};

struct Row {
    int id;
    std::string name;
    std::vector<Parameter> parameters;
    std::string description;
};

std::string trim(const std::string &text)
{
    const auto first = text.find_first_not_of(" `");
    const auto last = text.find_last_not_of(" `");
    return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string &text, const std::string &separator)
{
    std::vector<std::string> parts;
    size_t start = 0, found;
    while ((found = text.find(separator, start)) != std::string::npos) {
        parts.push_back(text.substr(start, found - start));
        start = found + separator.size();
    }
    parts.push_back(text.substr(start));
    return parts;
}

// Rows "| id | `name` | p: size, ... | description |" of language.md §13.1,
// copied in standard_natives.md; sizes use the typographic minus sign.
std::vector<Row> specification_table()
{
    std::ifstream file("tests/native_functions/standard_natives.md");
    std::vector<Row> rows;
    std::string line;
    while (std::getline(file, line)) {
        if (!line.starts_with("| ") || line.starts_with("| Id") || line.starts_with("|---"))
            continue;
        const auto cells = split(line, " | ");
        if (cells.size() != 4)
            continue;
        Row row;
        row.id = std::stoi(trim(cells[0].substr(1)));
        row.name = trim(cells[1]);
        for (const auto &parameter : split(cells[2], ", ")) {
            const auto parts = split(parameter, ": ");
            std::string size = trim(parts.at(1));
            int sign = 1;
            if (size.starts_with("\u2212")) {
                sign = -1;
                size = size.substr(std::string("\u2212").size());
            }
            row.parameters.push_back({ trim(parts.at(0)), sign * std::stoi(size) });
        }
        std::string description = cells[3];
        description = description.substr(0, description.rfind(" |"));
        row.description = description;
        rows.push_back(row);
    }
    return rows;
}

TEST(NativeDescriptions, MatchTheSpecificationTable)
{
    const auto rows = specification_table();
    ASSERT_EQ(rows.size(), 30u) << "could not read tests/native_functions/standard_natives.md";
    ASSERT_EQ(rows.size(), vm_native_count(&nat_standard_table));
    for (const Row &row : rows) {
        const auto native = description_of(*vm_native_at(&nat_standard_table, row.id));
        EXPECT_EQ(native.name, row.name);
        EXPECT_EQ(native.description, row.description) << row.name;
        ASSERT_EQ(native.parameters.size(), row.parameters.size()) << row.name;
        for (size_t p = 0; p < row.parameters.size(); ++p) {
            EXPECT_EQ(native.parameters[p].name, row.parameters[p].name) << row.name;
            EXPECT_EQ(native.parameters[p].size, row.parameters[p].size) << row.name;
        }
    }
}

TEST(NativeDescriptions, MatchTheReferenceDescriptions)
{
    const AsebaNativeFunctionDescription *reference[] = { ASEBA_NATIVES_STD_DESCRIPTIONS };
    ASSERT_EQ(sizeof reference / sizeof reference[0], vm_native_count(&nat_standard_table));
    for (uint16_t n = 0; n < vm_native_count(&nat_standard_table); ++n) {
        const auto native = description_of(*vm_native_at(&nat_standard_table, n));
        EXPECT_EQ(native.name, reference[n]->name);
        EXPECT_EQ(native.description, reference[n]->doc);
        size_t count = 0;
        while (reference[n]->arguments[count].size != 0)
            ++count;
        ASSERT_EQ(native.parameters.size(), count) << native.name;
        for (size_t p = 0; p < count; ++p) {
            EXPECT_EQ(native.parameters[p].name, reference[n]->arguments[p].name);
            EXPECT_EQ(native.parameters[p].size, reference[n]->arguments[p].size);
        }
    }
}

// Every native the project defines: the standard modules, then the DSP ones.
std::vector<vm_native> standard_and_dsp_natives()
{
    static const vm_native_module *const modules[] = { NAT_STANDARD_MODULES NAT_DSP_MODULES };
    const vm_native_table table{ modules, uint16_t(std::size(modules)), nullptr };
    return test_support::natives_of(table);
}

TEST(NativeDescriptions, StackWordsFollowTheCallingConvention)
{
    for (const vm_native &record : standard_and_dsp_natives()) {
        const vm_native *native = &record;
        const auto description = description_of(*native);
        size_t any_size = 0;
        std::set<int> templates;
        for (const auto &parameter : description.parameters) {
            if (parameter.size == 0)
                ++any_size;
            if (parameter.size < 0)
                templates.insert(parameter.size);
        }
        EXPECT_EQ(vm_native_stack_words(native),
                  description.parameters.size() + any_size + templates.size())
          << description.name;
        EXPECT_NE(native->function, nullptr) << description.name;
    }
}

// The W_ macros that descriptions are written with are the codes of the
// dictionary's words, and every byte from 0x80 in a description is a word.
TEST(NativeDescriptions, UseTheWordsOfTheDictionary)
{
    std::vector<std::string> words;
    for (const char *word = nat_words; *word != '\0'; word += std::strlen(word) + 1)
        words.push_back(word);
    int code = VM_NATIVE_WORD_FIRST;
#define CHECK_WORD(name, word_code, text)                                                          \
    EXPECT_EQ(word_code, code++) << #name;                                                         \
    EXPECT_EQ(static_cast<uint8_t>(W_##name[0]), word_code) << #name;                              \
    EXPECT_EQ(std::strlen(W_##name), 1u) << #name;                                                 \
    ASSERT_LT(size_t(word_code - VM_NATIVE_WORD_FIRST), words.size()) << #name;                    \
    EXPECT_EQ(words[size_t(word_code - VM_NATIVE_WORD_FIRST)], text) << #name;
    NAT_WORD_LIST(CHECK_WORD)
#undef CHECK_WORD
    EXPECT_EQ(size_t(code - VM_NATIVE_WORD_FIRST), words.size());

    for (const vm_native &record : standard_and_dsp_natives()) {
        const vm_native *native = &record;
        for (const char *byte = vm_native_name(native); *byte != '\0'; ++byte) {
            if (uint8_t(*byte) >= VM_NATIVE_WORD_FIRST) {
                EXPECT_LT(size_t(uint8_t(*byte) - VM_NATIVE_WORD_FIRST), words.size())
                  << description_of(*native).name;
            }
        }
    }
}

// A native's id is its place in the concatenation of the table's modules:
// the math module's 21, then the deque module's 9, and nothing after.
TEST(NativeDescriptions, ModulesFollowOneAnotherInTheTable)
{
    ASSERT_EQ(nat_math_module.count, 21);
    ASSERT_EQ(nat_deque_module.count, 9);
    ASSERT_EQ(vm_native_count(&nat_standard_table), 30);
    for (uint16_t n = 0; n < 21; ++n)
        EXPECT_EQ(vm_native_at(&nat_standard_table, n), &nat_math_module.natives[n]);
    for (uint16_t n = 0; n < 9; ++n)
        EXPECT_EQ(vm_native_at(&nat_standard_table, uint16_t(21 + n)),
                  &nat_deque_module.natives[n]);
    EXPECT_EQ(vm_native_at(&nat_standard_table, 30), nullptr);
    EXPECT_EQ(vm_native_at(&nat_standard_table, 4095), nullptr);
}

} // namespace
