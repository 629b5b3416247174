// The descriptions of the standard natives: names, documentation strings and
// parameters against the table of language.md §13.1 (read from the shared
// specification) and against Debian's reference descriptions; and the
// stack contract of bytecode.md §9.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "our_node.hpp"

extern "C" {
#include <aseba/vm/natives.h>
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
        if (!line.starts_with("| ") || line.starts_with("| Id") ||
            line.starts_with("|---"))
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
    ASSERT_EQ(nat_standard_table.count, NAT_STANDARD_COUNT);
    ASSERT_EQ(rows.size(), nat_standard_table.count);
    for (const Row &row : rows) {
        const vm_native &native = *nat_standard_table.natives[row.id];
        EXPECT_EQ(native.name, row.name);
        EXPECT_EQ(native.description, row.description) << row.name;
        ASSERT_EQ(native.parameter_count, row.parameters.size()) << row.name;
        for (size_t p = 0; p < row.parameters.size(); ++p) {
            EXPECT_EQ(native.parameters[p].name, row.parameters[p].name) << row.name;
            EXPECT_EQ(native.parameters[p].size, row.parameters[p].size) << row.name;
        }
    }
}

TEST(NativeDescriptions, MatchTheReferenceDescriptions)
{
    const AsebaNativeFunctionDescription *reference[] = { ASEBA_NATIVES_STD_DESCRIPTIONS };
    ASSERT_EQ(sizeof reference / sizeof reference[0], nat_standard_table.count);
    for (uint16_t n = 0; n < nat_standard_table.count; ++n) {
        const vm_native &native = *nat_standard_table.natives[n];
        EXPECT_STREQ(native.name, reference[n]->name);
        EXPECT_STREQ(native.description, reference[n]->doc);
        int count = 0;
        while (reference[n]->arguments[count].size != 0)
            ++count;
        ASSERT_EQ(native.parameter_count, count) << native.name;
        for (int p = 0; p < count; ++p) {
            EXPECT_STREQ(native.parameters[p].name, reference[n]->arguments[p].name);
            EXPECT_EQ(native.parameters[p].size, reference[n]->arguments[p].size);
        }
    }
}

TEST(NativeDescriptions, StackWordsFollowTheCallingConvention)
{
    for (uint16_t n = 0; n < nat_standard_table.count; ++n) {
        const vm_native &native = *nat_standard_table.natives[n];
        int any_size = 0;
        std::set<int> templates;
        for (int p = 0; p < native.parameter_count; ++p) {
            if (native.parameters[p].size == 0)
                ++any_size;
            if (native.parameters[p].size < 0)
                templates.insert(native.parameters[p].size);
        }
        EXPECT_EQ(native.stack_words, native.parameter_count + any_size + templates.size())
          << native.name;
        EXPECT_NE(native.function, nullptr) << native.name;
    }
}

TEST(NativeDescriptions, ListMacroGivesTheTableOrder)
{
    const vm_native *const listed[] = { NAT_STANDARD_LIST };
    ASSERT_EQ(sizeof listed / sizeof listed[0], static_cast<size_t>(NAT_STANDARD_COUNT));
    for (int n = 0; n < NAT_STANDARD_COUNT; ++n)
        EXPECT_EQ(listed[n], nat_standard_table.natives[n]);
}

} // namespace
