// Two passes: the first splits the listing into statements and gives every
// label its address, the second encodes the statements into words.

#include "tests/support/assembler.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <sstream>

#include "vm/vm_opcodes.h"

namespace test_support
{

AssemblyError::AssemblyError(unsigned line_number, const std::string &message)
  : std::runtime_error("line " + std::to_string(line_number) + ": " + message)
  , line(line_number)
{
}

namespace
{

struct OpcodeInfo {
    std::string name;
    uint16_t code;
    uint16_t words;
};

const std::vector<OpcodeInfo> &opcodes()
{
    static const std::vector<OpcodeInfo> list = {
#define ASSEMBLER_OPCODE(name, code, words, effect, meaning) { #name, code, words },
        VM_OPCODE_LIST(ASSEMBLER_OPCODE)
#undef ASSEMBLER_OPCODE
    };
    return list;
}

std::string upper(std::string_view text)
{
    std::string result(text);
    std::transform(result.begin(), result.end(), result.begin(), [](unsigned char c) {
        return static_cast<char>(std::toupper(c));
    });
    return result;
}

std::optional<int64_t> parse_number(std::string_view text)
{
    bool negative = false;
    if (!text.empty() && (text[0] == '-' || text[0] == '+')) {
        negative = text[0] == '-';
        text.remove_prefix(1);
    }
    int base = 10;
    if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
        base = 16;
        text.remove_prefix(2);
    }
    if (text.empty())
        return std::nullopt;
    int64_t value = 0;
    for (char c : text) {
        int digit;
        if (c >= '0' && c <= '9')
            digit = c - '0';
        else if (base == 16 && std::isxdigit(static_cast<unsigned char>(c)))
            digit = std::toupper(static_cast<unsigned char>(c)) - 'A' + 10;
        else
            return std::nullopt;
        value = value * base + digit;
        if (value > 0x7FFFFFFF)
            return std::nullopt;
    }
    return negative ? -value : value;
}

struct Statement {
    unsigned line;
    std::string mnemonic; // upper case; ".WORD" for raw words
    std::vector<std::string> operands;
    uint16_t address;
};

struct EventEntry {
    unsigned line;
    std::string event;
    std::string target;
};

class Assembler
{
  public:
    Program run(std::string_view listing);

  private:
    void parse_line(unsigned line, std::string_view text);
    uint16_t size_of(const Statement &statement) const;
    void encode(const Statement &statement);

    int64_t number(unsigned line, const std::string &text, int64_t low, int64_t high) const;
    uint16_t address_or_number(unsigned line, const std::string &text) const;
    uint16_t displacement(const Statement &statement,
                          const std::string &text,
                          int64_t low,
                          int64_t high) const;
    uint16_t binary_operator(unsigned line, const std::string &text) const;

    std::vector<Statement> statements_;
    std::vector<EventEntry> events_;
    std::vector<std::pair<unsigned, std::string>> pending_labels_;
    bool raw_ = false;
    Program program_;
};

std::vector<std::string> split_words(std::string_view text)
{
    std::vector<std::string> words;
    std::string current;
    for (char c : text) {
        if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
            if (!current.empty())
                words.push_back(current);
            current.clear();
        } else {
            current += c;
        }
    }
    if (!current.empty())
        words.push_back(current);
    return words;
}

void Assembler::parse_line(unsigned line, std::string_view text)
{
    size_t comment = text.find_first_of(";#");
    if (comment != std::string_view::npos)
        text = text.substr(0, comment);
    std::vector<std::string> words = split_words(text);
    // Labels end with ':' and may precede a statement on the same line.
    while (!words.empty() && words.front().back() == ':') {
        std::string name = words.front().substr(0, words.front().size() - 1);
        if (name.empty() || parse_number(name))
            throw AssemblyError(line, "bad label '" + words.front() + "'");
        pending_labels_.emplace_back(line, name);
        words.erase(words.begin());
    }
    if (words.empty())
        return;
    std::string mnemonic = upper(words.front());
    words.erase(words.begin());
    if (mnemonic == "EVENT") {
        if (words.size() != 2)
            throw AssemblyError(line, "event needs an event and a label or address");
        events_.push_back({ line, words[0], words[1] });
        return;
    }
    if (mnemonic == ".RAW") {
        raw_ = true;
        return;
    }
    statements_.push_back({ line, mnemonic, words, 0 });
    // Labels take the address of the statement that follows them.
    for (auto &[label_line, name] : pending_labels_)
        statements_.back().operands.insert(statements_.back().operands.begin(), ":" + name);
    pending_labels_.clear();
}

uint16_t Assembler::size_of(const Statement &statement) const
{
    if (statement.mnemonic == ".WORD") {
        size_t labels = std::count_if(statement.operands.begin(),
                                      statement.operands.end(),
                                      [](const std::string &o) { return o[0] == ':'; });
        return static_cast<uint16_t>(statement.operands.size() - labels);
    }
    for (const OpcodeInfo &opcode : opcodes()) {
        if (opcode.name == statement.mnemonic)
            return opcode.words;
    }
    throw AssemblyError(statement.line, "unknown mnemonic '" + statement.mnemonic + "'");
}

int64_t Assembler::number(unsigned line, const std::string &text, int64_t low, int64_t high) const
{
    std::optional<int64_t> value = parse_number(text);
    if (!value)
        throw AssemblyError(line, "bad number '" + text + "'");
    if (*value < low || *value > high) {
        std::ostringstream message;
        message << "operand " << text << " outside " << low << ".." << high;
        throw AssemblyError(line, message.str());
    }
    return *value;
}

uint16_t Assembler::address_or_number(unsigned line, const std::string &text) const
{
    auto label = program_.labels.find(text);
    if (label != program_.labels.end())
        return label->second;
    if (!parse_number(text))
        throw AssemblyError(line, "undefined label '" + text + "'");
    return static_cast<uint16_t>(number(line, text, INT16_MIN, UINT16_MAX));
}

// A label becomes the distance from the instruction's first word; a number
// is taken as the displacement itself.
uint16_t Assembler::displacement(const Statement &statement,
                                 const std::string &text,
                                 int64_t low,
                                 int64_t high) const
{
    auto label = program_.labels.find(text);
    int64_t value;
    if (label != program_.labels.end()) {
        value = static_cast<int64_t>(label->second) - statement.address;
        if (value < low || value > high)
            throw AssemblyError(statement.line, "label '" + text + "' too far");
    } else {
        if (!parse_number(text))
            throw AssemblyError(statement.line, "undefined label '" + text + "'");
        value = number(statement.line, text, low, high);
    }
    return static_cast<uint16_t>(value);
}

uint16_t Assembler::binary_operator(unsigned line, const std::string &text) const
{
    const std::vector<std::string> &names = binary_operator_names();
    for (size_t code = 0; code < names.size(); code++) {
        if (names[code] == upper(text))
            return static_cast<uint16_t>(code);
    }
    if (parse_number(text))
        return static_cast<uint16_t>(number(line, text, 0, VM_OPERATOR_MASK));
    throw AssemblyError(line, "unknown binary operator '" + text + "'");
}

void Assembler::encode(const Statement &statement)
{
    std::vector<std::string> operands;
    for (const std::string &operand : statement.operands) {
        if (operand[0] != ':')
            operands.push_back(operand);
    }
    const unsigned line = statement.line;
    std::vector<uint16_t> &out = program_.words;

    if (statement.mnemonic == ".WORD") {
        for (const std::string &operand : operands)
            out.push_back(address_or_number(line, operand));
        return;
    }

    const OpcodeInfo *info = nullptr;
    for (const OpcodeInfo &opcode : opcodes()) {
        if (opcode.name == statement.mnemonic)
            info = &opcode;
    }
    const uint16_t opcode = static_cast<uint16_t>(info->code << VM_OPCODE_SHIFT);
    auto expect_operands = [&](size_t low, size_t high) {
        if (operands.size() < low || operands.size() > high)
            throw AssemblyError(line, statement.mnemonic + ": wrong number of operands");
    };
    auto operand12 = [&](const std::string &text) {
        return static_cast<uint16_t>(number(line, text, 0, VM_OPERAND_MASK));
    };
    auto word16 = [&](const std::string &text) {
        return static_cast<uint16_t>(number(line, text, INT16_MIN, UINT16_MAX));
    };

    switch (info->code) {
    case VM_OP_STOP:
    case VM_OP_SUB_RET:
        expect_operands(0, 0);
        out.push_back(opcode);
        break;
    case VM_OP_SMALL_IMMEDIATE:
        expect_operands(1, 1);
        out.push_back(opcode | (static_cast<uint16_t>(number(line, operands[0], -2048, 2047)) &
                                VM_OPERAND_MASK));
        break;
    case VM_OP_LARGE_IMMEDIATE:
        expect_operands(1, 1);
        out.push_back(opcode);
        out.push_back(address_or_number(line, operands[0]));
        break;
    case VM_OP_LOAD:
    case VM_OP_STORE:
    case VM_OP_NATIVE_CALL:
        expect_operands(1, 1);
        out.push_back(opcode | operand12(operands[0]));
        break;
    case VM_OP_LOAD_INDIRECT:
    case VM_OP_STORE_INDIRECT:
        expect_operands(2, 2);
        out.push_back(opcode | operand12(operands[0]));
        out.push_back(word16(operands[1]));
        break;
    case VM_OP_UNARY_ARITHMETIC: {
        expect_operands(1, 1);
        const std::vector<std::string> &names = unary_operator_names();
        auto found = std::find(names.begin(), names.end(), upper(operands[0]));
        uint16_t code = found != names.end()
                          ? static_cast<uint16_t>(found - names.begin())
                          : static_cast<uint16_t>(number(line, operands[0], 0, VM_OPERAND_MASK));
        out.push_back(opcode | code);
        break;
    }
    case VM_OP_BINARY_ARITHMETIC:
        expect_operands(1, 1);
        out.push_back(opcode | binary_operator(line, operands[0]));
        break;
    case VM_OP_JUMP:
        expect_operands(1, 1);
        out.push_back(opcode |
                      (displacement(statement, operands[0], -2048, 2047) & VM_OPERAND_MASK));
        break;
    case VM_OP_CONDITIONAL_BRANCH: {
        expect_operands(2, 4);
        uint16_t word = opcode | binary_operator(line, operands[0]);
        for (size_t i = 2; i < operands.size(); i++) {
            std::string flag = upper(operands[i]);
            if (flag == "WHEN")
                word |= VM_BRANCH_IS_WHEN_BIT;
            else if (flag == "WAS_TRUE")
                word |= VM_BRANCH_WAS_TRUE_BIT;
            else
                throw AssemblyError(line, "unknown branch flag '" + operands[i] + "'");
        }
        out.push_back(word);
        out.push_back(displacement(statement, operands[1], INT16_MIN, INT16_MAX));
        break;
    }
    case VM_OP_EMIT:
        expect_operands(3, 3);
        out.push_back(opcode | operand12(operands[0]));
        out.push_back(word16(operands[1]));
        out.push_back(word16(operands[2]));
        break;
    case VM_OP_SUB_CALL: {
        expect_operands(1, 1);
        uint16_t target = address_or_number(line, operands[0]);
        if (target > VM_OPERAND_MASK)
            throw AssemblyError(line, "subroutine address does not fit 12 bits");
        out.push_back(opcode | target);
        break;
    }
    default: throw AssemblyError(line, "unhandled mnemonic " + statement.mnemonic);
    }
}

Program Assembler::run(std::string_view listing)
{
    unsigned line = 0;
    size_t start = 0;
    while (start <= listing.size()) {
        size_t end = listing.find('\n', start);
        if (end == std::string_view::npos)
            end = listing.size();
        parse_line(++line, listing.substr(start, end - start));
        start = end + 1;
    }
    if (raw_ && !events_.empty())
        throw AssemblyError(events_.front().line, "event table with .raw");

    // First pass: addresses. The table comes first unless the image is raw.
    uint32_t address = raw_ ? 0 : 2 * events_.size() + 1;
    for (Statement &statement : statements_) {
        statement.address = static_cast<uint16_t>(address);
        for (const std::string &operand : statement.operands) {
            if (operand[0] != ':')
                continue;
            if (!program_.labels.emplace(operand.substr(1), statement.address).second)
                throw AssemblyError(statement.line, "duplicate label '" + operand.substr(1) + "'");
        }
        address += size_of(statement);
        if (address > UINT16_MAX)
            throw AssemblyError(statement.line, "image larger than 65535 words");
    }
    for (auto &[label_line, name] : pending_labels_) { // labels at the very end
        if (!program_.labels.emplace(name, static_cast<uint16_t>(address)).second)
            throw AssemblyError(label_line, "duplicate label '" + name + "'");
    }

    // Second pass: words.
    if (!raw_) {
        program_.words.push_back(static_cast<uint16_t>(2 * events_.size() + 1));
        for (const EventEntry &entry : events_) {
            uint16_t id = upper(entry.event) == "INIT" ? VM_EVENT_INIT
                                                       : address_or_number(entry.line, entry.event);
            program_.words.push_back(id);
            program_.words.push_back(address_or_number(entry.line, entry.target));
        }
    }
    for (const Statement &statement : statements_)
        encode(statement);
    return program_;
}

} // namespace

Program assemble(std::string_view listing)
{
    return Assembler().run(listing);
}

const std::vector<std::string> &binary_operator_names()
{
    static const std::vector<std::string> names = [] {
        std::vector<std::string> list(VM_BINARY_OPERATOR_COUNT);
#define ASSEMBLER_BINARY(name, code, token) list[code] = #name;
        VM_BINARY_OPERATOR_LIST(ASSEMBLER_BINARY)
#undef ASSEMBLER_BINARY
        return list;
    }();
    return names;
}

const std::vector<std::string> &unary_operator_names()
{
    static const std::vector<std::string> names = [] {
        std::vector<std::string> list(VM_UNARY_OPERATOR_COUNT);
#define ASSEMBLER_UNARY(name, code, token) list[code] = #name;
        VM_UNARY_OPERATOR_LIST(ASSEMBLER_UNARY)
#undef ASSEMBLER_UNARY
        return list;
    }();
    return names;
}

} // namespace test_support
