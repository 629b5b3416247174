// Turns bytecode back into readable instructions (bytecode.md §3), for
// listings of the compiler and the console's debugger.

#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace aseba
{

struct DisassembledInstruction {
    uint16_t address = 0;
    std::vector<uint16_t> words;
    std::string text; // mnemonic and operands, e.g. "LOAD 36" or "JUMP -5 (-> 12)"
};

// The instructions of `bytecode` from its code start (after the event table),
// never reading past its end (a truncated instruction is shown as such).
std::vector<DisassembledInstruction> disassemble(const std::vector<uint16_t> &bytecode);

// The instruction starting at `address`.
DisassembledInstruction disassemble_at(const std::vector<uint16_t> &bytecode, uint16_t address);

// A listing: the event table, then one line per instruction with address,
// words, mnemonic and, when `line_of_word` is given, the source line number
// and text taken from `source`.
std::string listing(const std::vector<uint16_t> &bytecode,
                    const std::vector<unsigned> &line_of_word = {},
                    std::string_view source = {});

} // namespace aseba
