// The decoded-once form of an instruction: the operand fields of a program
// word pulled out by its format (isa.hpp) into a compact record, made when
// the word is first executed and kept until the flash row holding it is
// written.

#pragma once

#include "tools/dspic30_sim/isa.hpp"

#include <cstdint>

namespace aseba::dspic30
{

// The `op` of a record not decoded yet (flash loaded or written since).
inline constexpr Op op_undecoded = static_cast<Op>(0xFF);

// One predecoded instruction. Which field means what depends on the format
// (predecode.cpp says it per format); the names give the common use.
struct Decoded {
    Op op = op_undecoded;
    uint8_t words = 1;  // 1, or 2 for GOTO, CALL and DO
    uint8_t cycles = 1; // the manual's base count
    uint8_t byte = 0;   // byte operation; in DSP forms the accumulator (0 = A, 1 = B)
    uint8_t ws = 0;     // source register
    uint8_t wd = 0;     // destination register
    uint8_t wb = 0;     // base, offset or second operand register
    uint8_t smode = 0;  // AddrMode of ws; X prefetch field in the MAC class
    uint8_t dmode = 0;  // AddrMode of wd; Y prefetch field in the MAC class
    uint8_t aux = 0;    // bit number, condition, D bit, literal flag, Y destination
    uint16_t lit = 0;   // literal or file-register address
    int32_t imm = 0;    // branch target PC, signed offset or shift
};

static_assert(sizeof(Decoded) == 16, "one cache line holds four instructions");

// The record of the instruction `word` at `pc`; `next_word` is the program
// word after it (the second word of GOTO, CALL and DO).
Decoded predecode(uint32_t pc, uint32_t word, uint32_t next_word);

} // namespace aseba::dspic30
