// The disassembler. Names come from the opcode and operator lists of
// vm/vm_opcodes.h, the same lists the VM is written from.

#include "disassembler.hpp"

#include <cstdio>
#include <sstream>

#include "vm_opcodes.h"

namespace aseba
{

namespace
{

constexpr unsigned TWELVE_BIT_SIGN = 0x800;
constexpr int TWELVE_BIT_RANGE = 0x1000;
constexpr uint16_t EVENT_TABLE_WORD = 0;

const char *opcode_name(unsigned opcode)
{
    switch (opcode) {
#define OPCODE_NAME(name, code, words, effect, meaning)                                            \
    case code: return #name;
        VM_OPCODE_LIST(OPCODE_NAME)
#undef OPCODE_NAME
    default: return "INVALID";
    }
}

unsigned opcode_words(unsigned opcode)
{
    switch (opcode) {
#define OPCODE_WORDS(name, code, words, effect, meaning)                                           \
    case code: return words;
        VM_OPCODE_LIST(OPCODE_WORDS)
#undef OPCODE_WORDS
    default: return 1;
    }
}

std::string binary_operator(unsigned code)
{
    switch (code) {
#define BINARY_NAME(name, value, token)                                                            \
    case value: return token;
        VM_BINARY_OPERATOR_LIST(BINARY_NAME)
#undef BINARY_NAME
    default: return "?" + std::to_string(code);
    }
}

std::string unary_operator(unsigned code)
{
    switch (code) {
#define UNARY_NAME(name, value, token)                                                             \
    case value: return token;
        VM_UNARY_OPERATOR_LIST(UNARY_NAME)
#undef UNARY_NAME
    default: return "?" + std::to_string(code);
    }
}

int signed_twelve_bits(unsigned operand)
{
    return (operand & TWELVE_BIT_SIGN) ? static_cast<int>(operand) - TWELVE_BIT_RANGE
                                       : static_cast<int>(operand);
}

std::string hex_word(uint16_t word)
{
    char text[8];
    std::snprintf(text, sizeof text, "%04x", word);
    return text;
}

} // namespace

DisassembledInstruction disassemble_at(const std::vector<uint16_t> &bytecode, uint16_t address)
{
    DisassembledInstruction result;
    result.address = address;
    if (address >= bytecode.size())
        return result;
    uint16_t first = bytecode[address];
    unsigned opcode = first >> VM_OPCODE_SHIFT;
    unsigned operand = first & VM_OPERAND_MASK;
    unsigned length = opcode_words(opcode);
    for (unsigned i = 0; i < length && address + i < bytecode.size(); ++i)
        result.words.push_back(bytecode[address + i]);
    if (result.words.size() < length) {
        result.text = std::string(opcode_name(opcode)) + " (truncated)";
        return result;
    }
    std::string text = opcode_name(opcode);
    auto word = [&result](unsigned i) { return result.words[i]; };
    switch (opcode) {
    case VM_OP_SMALL_IMMEDIATE: text += " " + std::to_string(signed_twelve_bits(operand)); break;
    case VM_OP_LARGE_IMMEDIATE: text += " " + std::to_string(static_cast<int16_t>(word(1))); break;
    case VM_OP_LOAD:
    case VM_OP_STORE: text += " " + std::to_string(operand); break;
    case VM_OP_LOAD_INDIRECT:
    case VM_OP_STORE_INDIRECT:
        text += " " + std::to_string(operand) + " size " + std::to_string(word(1));
        break;
    case VM_OP_UNARY_ARITHMETIC: text += " " + unary_operator(operand & VM_OPERATOR_MASK); break;
    case VM_OP_BINARY_ARITHMETIC: text += " " + binary_operator(operand & VM_OPERATOR_MASK); break;
    case VM_OP_JUMP: {
        int offset = signed_twelve_bits(operand);
        text += " " + std::to_string(offset) + " (-> " + std::to_string(address + offset) + ")";
        break;
    }
    case VM_OP_CONDITIONAL_BRANCH: {
        int offset = static_cast<int16_t>(word(1));
        text += std::string((operand & VM_BRANCH_IS_WHEN_BIT) ? " when " : " if ") +
                binary_operator(operand & VM_OPERATOR_MASK) + " else " + std::to_string(offset) +
                " (-> " + std::to_string(address + offset) + ")";
        break;
    }
    case VM_OP_EMIT:
        text += " event " + std::to_string(operand) + " from " + std::to_string(word(1)) +
                " size " + std::to_string(word(2));
        break;
    case VM_OP_NATIVE_CALL:
    case VM_OP_SUB_CALL: text += " " + std::to_string(operand); break;
    default: break;
    }
    result.text = text;
    return result;
}

std::vector<DisassembledInstruction> disassemble(const std::vector<uint16_t> &bytecode)
{
    std::vector<DisassembledInstruction> instructions;
    if (bytecode.empty())
        return instructions;
    size_t address = bytecode[EVENT_TABLE_WORD];
    while (address < bytecode.size()) {
        DisassembledInstruction instruction =
          disassemble_at(bytecode, static_cast<uint16_t>(address));
        address += instruction.words.empty() ? 1 : instruction.words.size();
        instructions.push_back(std::move(instruction));
    }
    return instructions;
}

std::string listing(const std::vector<uint16_t> &bytecode,
                    const std::vector<unsigned> &line_of_word,
                    std::string_view source)
{
    std::vector<std::string_view> lines;
    size_t start = 0;
    while (start <= source.size() && !source.empty()) {
        size_t end = source.find('\n', start);
        if (end == std::string_view::npos)
            end = source.size();
        std::string_view line = source.substr(start, end - start);
        if (!line.empty() && line.back() == '\r')
            line.remove_suffix(1);
        lines.push_back(line);
        start = end + 1;
    }
    std::ostringstream out;
    if (bytecode.empty())
        return "";
    out << "event table (" << bytecode[0] << " words):\n";
    for (size_t i = 1; i + 1 < bytecode.size() && i < bytecode[0]; i += 2)
        out << "  event 0x" << hex_word(bytecode[i]) << " at " << bytecode[i + 1] << "\n";
    unsigned previous_line = 0;
    for (const auto &instruction : disassemble(bytecode)) {
        std::string words;
        for (uint16_t word : instruction.words)
            words += hex_word(word) + " ";
        char prefix[64];
        std::snprintf(prefix, sizeof prefix, "%5u: %-16s", instruction.address, words.c_str());
        out << prefix << instruction.text;
        unsigned line =
          instruction.address < line_of_word.size() ? line_of_word[instruction.address] : 0;
        if (line != 0 && line != previous_line) {
            out << "    ; line " << line;
            if (line <= lines.size())
                out << ": " << lines[line - 1];
            previous_line = line;
        }
        out << "\n";
    }
    return out.str();
}

} // namespace aseba
