// Instruction text in the syntax of Microchip's disassembler
// (pic30-elf-objdump -d), which tests/dspic30_sim compares it with; the
// only spacing is one space after the mnemonic and ", " between operands.

#pragma once

#include <cstdint>
#include <string>

namespace aseba::dspic30
{

// The text of the instruction `word` at program address `pc`; `next_word`
// is the word after it, the second word of GOTO, CALL and DO. A word that
// is no instruction reads ".pword 0x......".
std::string disassemble(uint32_t pc, uint32_t word, uint32_t next_word);

// How many program words the instruction `word` takes (1, or 2 for GOTO,
// CALL and DO).
int instruction_words(uint32_t word);

} // namespace aseba::dspic30
