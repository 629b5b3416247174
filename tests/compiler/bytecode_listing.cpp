// Decodes bytecode for diagnostics only; nothing here is compared by a test.

#include "bytecode_listing.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace compiler_tests
{

namespace
{

const char *const binary_operators[] = { "<<", ">>", "+",  "-", "*",  "/", "%",  "|",  "^",
                                         "&",  "==", "!=", ">", ">=", "<", "<=", "or", "and" };
const char *const unary_operators[] = { "neg", "abs", "~", "not" };

constexpr unsigned opcode_shift = 12;
constexpr uint16_t operand_mask = 0x0FFF;
constexpr uint16_t operator_mask = 0x00FF;
constexpr uint16_t when_bit = 0x0100;
constexpr uint16_t sign_bit_12 = 0x0800;

int signed12(uint16_t word)
{
    const int value = word & operand_mask;
    return (value & sign_bit_12) ? value - 0x1000 : value;
}

std::string hex(uint16_t word)
{
    char text[8];
    std::snprintf(text, sizeof text, "%04x", word);
    return text;
}

std::string operator_name(uint16_t word, bool binary)
{
    const unsigned code = word & operator_mask;
    if (binary && code < std::size(binary_operators))
        return binary_operators[code];
    if (!binary && code < std::size(unary_operators))
        return unary_operators[code];
    return "op?" + std::to_string(code);
}

// Number of words of the instruction starting with `word` (bytecode.md §3).
std::size_t instruction_length(uint16_t word)
{
    switch (word >> opcode_shift) {
    case 0x2:
    case 0x5:
    case 0x6:
    case 0xA: return 2;
    case 0xB: return 3;
    default: return 1;
    }
}

std::string decode(const std::vector<uint16_t> &code, std::size_t at)
{
    const uint16_t word = code[at];
    const uint16_t operand = word & operand_mask;
    auto extra = [&](std::size_t k) {
        return at + k < code.size() ? std::to_string(code[at + k]) : std::string("<missing>");
    };
    auto extra_signed = [&](std::size_t k) {
        return at + k < code.size() ? std::to_string(int16_t(code[at + k]))
                                    : std::string("<missing>");
    };
    switch (word >> opcode_shift) {
    case 0x0: return "STOP";
    case 0x1: return "SMALL_IMMEDIATE " + std::to_string(signed12(word));
    case 0x2: return "LARGE_IMMEDIATE " + extra_signed(1);
    case 0x3: return "LOAD " + std::to_string(operand);
    case 0x4: return "STORE " + std::to_string(operand);
    case 0x5: return "LOAD_INDIRECT " + std::to_string(operand) + ", size " + extra(1);
    case 0x6: return "STORE_INDIRECT " + std::to_string(operand) + ", size " + extra(1);
    case 0x7: return "UNARY " + operator_name(word, false);
    case 0x8: return "BINARY " + operator_name(word, true);
    case 0x9:
        return "JUMP " + std::to_string(signed12(word)) + " -> " +
               std::to_string(long(at) + signed12(word));
    case 0xA: {
        const int offset = at + 1 < code.size() ? int16_t(code[at + 1]) : 0;
        return std::string(word & when_bit ? "WHEN_BRANCH " : "IF_BRANCH ") +
               operator_name(word, true) + ", if false -> " + std::to_string(long(at) + offset);
    }
    case 0xB:
        return "EMIT " + std::to_string(operand) + ", from " + extra(1) + ", " + extra(2) +
               " words";
    case 0xC: return "NATIVE_CALL " + std::to_string(operand);
    case 0xD: return "SUB_CALL " + std::to_string(operand);
    case 0xE: return "SUB_RET";
    default: return "<invalid opcode>";
    }
}

std::vector<std::string> listing_lines(const std::vector<uint16_t> &bytecode)
{
    std::vector<std::string> lines;
    if (bytecode.empty())
        return lines;
    const std::size_t table_end = std::min<std::size_t>(bytecode[0], bytecode.size());
    lines.push_back("   0: " + hex(bytecode[0]) + "            event table of " +
                    std::to_string(bytecode[0] / 2) + " events");
    for (std::size_t i = 1; i + 1 < table_end; i += 2)
        lines.push_back("   " + std::to_string(i) + ": " + hex(bytecode[i]) + " " +
                        hex(bytecode[i + 1]) + "       event " + hex(bytecode[i]) + " at " +
                        std::to_string(bytecode[i + 1]));
    for (std::size_t at = table_end; at < bytecode.size();) {
        const std::size_t length = instruction_length(bytecode[at]);
        std::string words;
        for (std::size_t k = 0; k < 3; ++k)
            words += (k < length && at + k < bytecode.size()) ? hex(bytecode[at + k]) + " "
                                                              : std::string(5, ' ');
        char address[32];
        std::snprintf(address, sizeof address, "%4zu: ", at);
        lines.push_back(address + words + decode(bytecode, at));
        at += length;
    }
    return lines;
}

} // namespace

std::string bytecode_listing(const std::vector<uint16_t> &bytecode)
{
    std::string text;
    for (const std::string &line : listing_lines(bytecode))
        text += line + "\n";
    return text;
}

std::string compare_listings(const std::vector<uint16_t> &left,
                             const std::vector<uint16_t> &right,
                             const std::string &left_title,
                             const std::string &right_title)
{
    const std::vector<std::string> left_lines = listing_lines(left);
    const std::vector<std::string> right_lines = listing_lines(right);
    constexpr std::size_t column_width = 52;
    std::ostringstream text;
    std::string title = left_title;
    title.resize(column_width, ' ');
    text << "  " << title << right_title << "\n";
    for (std::size_t i = 0; i < std::max(left_lines.size(), right_lines.size()); ++i) {
        const std::string l = i < left_lines.size() ? left_lines[i] : "";
        const std::string r = i < right_lines.size() ? right_lines[i] : "";
        std::string padded = l;
        padded.resize(std::max(column_width, l.size() + 1), ' ');
        text << (l == r ? "  " : "! ") << padded << r << "\n";
    }
    return text.str();
}

} // namespace compiler_tests
