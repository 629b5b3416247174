// The dsPIC30F instruction set as data: the operation list of
// instructions.def turned into an enum and a table, the operand formats and
// the decoding of a 24-bit program word (16-bit MCU and DSC Programmer's
// Reference Manual, DS70157). The disassembler (disassembler.hpp) and the
// executor (cpu.hpp) are both driven by this one table.

#pragma once

#include <cstdint>
#include <string_view>

namespace aseba::dspic30
{

// Operand formats: which fields a word carries and where (instructions.def
// lists the field layouts; isa.cpp checks each format's addressing modes).
enum Format : uint8_t {
    F_NONE,       // no operand
    F_W,          // Wn in bits 3:0
    F_ABS23,      // 2 words: address<15:0> in word 1, address<22:16> in word 2
    F_RETLW,      // #lit10 (bits 13:4), Wn
    F_REL16,      // slit16 word offset from PC + 2
    F_BRA_COND,   // condition in bits 19:16, slit16
    F_BRA_DSP,    // OA/OB/SA/SB in bits 17:16, slit16
    F_DO_LIT,     // 2 words: #lit14, slit16 in word 2
    F_DO_W,       // 2 words: Wn, slit16 in word 2
    F_LIT14,      // #lit14 (REPEAT, LNK, DISI)
    F_3OP,        // Wb, Ws or #lit5, Wd
    F_MOV_LIT16,  // #lit16 (bits 19:4), Wn
    F_MOV,        // Ws, Wd, both may be [W+Wb]
    F_MOV_F_W,    // f<15:1> in bits 18:4, Wn
    F_MOV_W_F,    // Wn, f<15:1>
    F_MOV_LDO,    // [Ws + slit10], Wd
    F_MOV_STO,    // Ws, [Wd + slit10]
    F_BIT4_WS,    // Ws, #bit4 (bits 15:12)
    F_BIT3_WS,    // byte Ws, #bit3 (bits 14:12)
    F_BIT_WB,     // Ws, Wb (bits 14:11)
    F_BIT3_F,     // f (bits 12:0), #bit3 (bits 15:13)
    F_LIT10_W,    // #lit10, Wn
    F_MOV_LIT8,   // #lit8 (bits 11:4), Wn
    F_FILE,       // f {,WREG}: D = bit 13
    F_FILE_ONLY,  // f (no destination bit)
    F_WREG_F,     // WREG, f
    F_CLR_F,      // f, or WREG when D = 0 (then f must be 0)
    F_MUL,        // Wb, Ws or #lit5, Wnd (even)
    F_MUL_WS,     // Wb, Ws, Wnd (even)
    F_TBL,        // Ws, Wd (no register offset)
    F_MOVD_LOAD,  // Ws, Wnd
    F_MOVD_STORE, // Wns, Wd
    F_MAC,        // Wm*Wn, Acc, X and Y prefetch, write-back
    F_MAC_CLR,    // Acc, X and Y prefetch, write-back (CLR, MOVSAC)
    F_SQR,        // Wm*Wm, Acc, X and Y prefetch
    F_ED,         // Wm*Wm, Acc, X and Y prefetch (both subtracted), Wxd
    F_SFTAC,      // Acc, #slit6 or Wb
    F_ACC_WS,     // Ws (or [Ws+Wb]), #slit4, Acc
    F_ACC,        // Acc
    F_SAC,        // Acc, #slit4, Wd (or [Wd+Wb])
    F_WS_WND,     // Ws, Wnd
    F_WS_WD,      // Ws, Wd
    F_WD,         // Wd
    F_DIV,        // Wm (bits 10:7), Wn
    F_DIVF,       // Wm (bits 14:11), Wn
    F_SHIFT,      // Wb, #lit4 or Wns, Wnd
    F_CP0_WS,     // Ws
    F_CP_WS,      // Wb, Ws or #lit5
    F_CPS,        // Wb, Wn
    F_PUSHPOP,    // f (16 bits)
    F_EXCH,       // Wns, Wnd
    F_PWRSAV,     // #lit1
};

// How the disassembler spells the operand size after the mnemonic.
enum Suffix : uint8_t {
    S_NONE, // nothing (or the mnemonic carries it)
    S_W,    // always .w
    S_B,    // always .b
    S_B14,  // .b when bit 14 is set, else .w
    S_B10,  // .b when bit 10 is set, else .w
};

// What the executor must know of an instruction beyond its semantics.
enum Attr : uint8_t {
    A_NONE = 0,
    A_FLOW = 1, // changes the PC
    A_COND = 2, // conditional branch: one more cycle when taken
    A_SKIP = 4, // may skip the next instruction (one or two more cycles)
    A_LOOP = 8, // REPEAT or DO
    A_DSP = 16, // DSP engine instruction
    A_DIV = 32, // one iteration of a divide (REPEAT #17 target)
};

// Every operation of instructions.def, in its order; INVALID is a word that
// decodes as no instruction.
enum class Op : uint8_t {
#define INSN(name, mnemonic, match, mask, format, suffix, words, cycles, attrs) name,
#include "instructions.def"
#undef INSN
    INVALID,
};

inline constexpr int op_count = static_cast<int>(Op::INVALID);

// One row of instructions.def.
struct InsnInfo {
    std::string_view mnemonic;
    uint32_t match;
    uint32_t mask;
    Format format;
    Suffix suffix;
    uint8_t words;
    uint8_t cycles;
    uint8_t attrs;
};

// The row of `op` (op != Op::INVALID).
const InsnInfo &insn_info(Op op);

// The operation a 24-bit program word encodes, or Op::INVALID.
Op decode_op(uint32_t word);

// Addressing modes of the Ws (ppp) and Wd (qqq) fields.
enum AddrMode : uint8_t {
    AM_DIRECT = 0,   // Wn
    AM_INDIRECT = 1, // [Wn]
    AM_POSTDEC = 2,  // [Wn--]
    AM_POSTINC = 3,  // [Wn++]
    AM_PREDEC = 4,   // [--Wn]
    AM_PREINC = 5,   // [++Wn]
    AM_OFFSET = 6,   // [Wn+Wb]
    AM_LITERAL = 7,  // #lit5 (Ws of the math and compare forms: ppp = 11x)
};

// Bits hi..lo of `word`.
constexpr uint32_t field(uint32_t word, int hi, int lo)
{
    return (word >> lo) & ((1u << (hi - lo + 1)) - 1);
}

// Bit `n` of `word`.
constexpr bool bit(uint32_t word, int n)
{
    return ((word >> n) & 1u) != 0;
}

// `value` of `bits` bits, sign-extended.
constexpr int32_t sign_extend(uint32_t value, int bits)
{
    const uint32_t sign = 1u << (bits - 1);
    return static_cast<int32_t>((value ^ sign) - sign);
}

// Word fields shared by several formats.
namespace fields
{
constexpr int ws(uint32_t w)
{
    return static_cast<int>(field(w, 3, 0));
}
constexpr int ppp(uint32_t w)
{
    return static_cast<int>(field(w, 6, 4));
}
constexpr int wd(uint32_t w)
{
    return static_cast<int>(field(w, 10, 7));
}
constexpr int qqq(uint32_t w)
{
    return static_cast<int>(field(w, 13, 11));
}
constexpr int wb_high(uint32_t w) // Wb of the three-operand and MOV forms
{
    return static_cast<int>(field(w, 18, 15));
}
constexpr int wb_low(uint32_t w) // Wb of the forms with bits 14:11
{
    return static_cast<int>(field(w, 14, 11));
}
// The signed 10-bit literal of MOV [Ws+slit10],Wd and MOV Ws,[Wd+slit10],
// spread over bits 18:15, 13:11 and 6:4.
constexpr int32_t slit10(uint32_t w)
{
    return sign_extend((field(w, 18, 15) << 6) | (field(w, 13, 11) << 3) | field(w, 6, 4), 10);
}
} // namespace fields

// The MAC-class prefetch field values that do no prefetch, and that use
// the W12 offset ([W9+W12] or [W11+W12]).
inline constexpr int prefetch_none = 4;
inline constexpr int prefetch_offset = 12;

} // namespace aseba::dspic30
