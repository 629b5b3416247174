// The instruction table of instructions.def and the decoding of a word: the
// first row of its top byte whose mask and match fit and whose operand
// fields are legal for the form.

#include "tools/dspic30_sim/isa.hpp"

#include <array>
#include <vector>

namespace aseba::dspic30
{
namespace
{

constexpr std::array<InsnInfo, op_count> table = { {
#define INSN(name, mnemonic, match, mask, format, suffix, words, cycles, attrs)                    \
    { mnemonic, match, mask, format, suffix, words, cycles, attrs },
#include "tools/dspic30_sim/instructions.def"
#undef INSN
} };

// The highest addressing mode a field may hold in each format: the modes
// above it make the word invalid (AM_LITERAL where the form takes #lit5).
constexpr int last_memory_mode = AM_PREINC;

constexpr int mac_pair_clr = 3;    // mmm of CLR: no multiplicand pair
constexpr int mac_pair_movsac = 7; // mmm of MOVSAC
constexpr int awb_reserved = 3;    // write-back field value of MPY/MPY.N

// Whether the operand fields of `word` are legal for `format`.
bool fields_valid(Format format, uint32_t word)
{
    using namespace fields;
    switch (format) {
    case F_3OP: return qqq(word) <= last_memory_mode;
    case F_MOV: return ppp(word) <= AM_OFFSET && qqq(word) <= AM_OFFSET;
    case F_BIT4_WS:
    case F_BIT3_WS:
    case F_BIT_WB:
    case F_MUL_WS:
    case F_MOVD_LOAD:
    case F_WS_WND:
    case F_CP0_WS: return ppp(word) <= last_memory_mode;
    case F_TBL:
    case F_WS_WD: return ppp(word) <= last_memory_mode && qqq(word) <= last_memory_mode;
    case F_MOVD_STORE:
    case F_WD: return qqq(word) <= last_memory_mode;
    case F_ACC_WS:
    case F_SAC: return ppp(word) <= AM_OFFSET;
    case F_MAC: {
        const int pair = static_cast<int>(field(word, 18, 16));
        return pair != mac_pair_clr && pair != mac_pair_movsac;
    }
    case F_MAC_CLR: return static_cast<int>(field(word, 1, 0)) != awb_reserved;
    case F_CLR_F: return bit(word, 13) || field(word, 12, 0) == 0;
    default: return true;
    }
}

// The rows that may match each top byte, in table order.
struct Buckets {
    std::array<std::vector<uint8_t>, 256> rows;
    Buckets()
    {
        for (int top = 0; top < 256; ++top)
            for (int op = 0; op < op_count; ++op) {
                const uint32_t mask_top = table[op].mask >> 16;
                if ((static_cast<uint32_t>(top) & mask_top) == (table[op].match >> 16))
                    rows[top].push_back(static_cast<uint8_t>(op));
            }
    }
};

} // namespace

const InsnInfo &insn_info(Op op)
{
    return table[static_cast<int>(op)];
}

Op decode_op(uint32_t word)
{
    static const Buckets buckets;
    for (uint8_t op : buckets.rows[field(word, 23, 16)]) {
        const InsnInfo &info = table[op];
        if ((word & info.mask) == info.match && fields_valid(info.format, word))
            return static_cast<Op>(op);
    }
    return Op::INVALID;
}

} // namespace aseba::dspic30
