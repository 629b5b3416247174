// Operand fields per format, into the Decoded record. Addresses are
// resolved here once: branch targets and DO loop ends become absolute PCs,
// MOV [W+slit10] offsets are scaled to bytes, literals are masked to the
// operation size.

#include "tools/dspic30_sim/predecode.hpp"

#include "tools/dspic30_sim/memory_map.hpp"

#include <array>

namespace aseba::dspic30
{
namespace
{

using namespace fields;

constexpr int literal_mode_first = AM_OFFSET; // ppp = 11x is #lit5 where a form allows it
constexpr uint16_t byte_literal_mask = 0xFF;
constexpr int prefetch_destination = 4; // W4..W7

uint8_t u8(uint32_t v)
{
    return static_cast<uint8_t>(v);
}

// The Ws mode of the forms where ppp = 11x means #lit5.
uint8_t source_mode_or_literal(uint32_t w)
{
    return ppp(w) >= literal_mode_first ? static_cast<uint8_t>(AM_LITERAL) : u8(ppp(w));
}

int32_t relative_target(uint32_t pc, uint32_t w)
{
    return static_cast<int32_t>((pc + 2 + 2 * sign_extend(field(w, 15, 0), 16)) & pc_mask);
}

// The MAC-class multiplicand pairs by their mmm field (3 and 7 are CLR and
// MOVSAC, which multiply nothing).
constexpr std::array<std::array<uint8_t, 2>, 8> mac_pairs = {
    { { 4, 5 }, { 4, 6 }, { 4, 7 }, { 0, 0 }, { 5, 6 }, { 5, 7 }, { 6, 7 }, { 0, 0 } }
};

} // namespace

Decoded predecode(uint32_t pc, uint32_t w, uint32_t next)
{
    Decoded d;
    d.op = decode_op(w);
    if (d.op == Op::INVALID)
        return d;
    const InsnInfo &info = insn_info(d.op);
    d.words = info.words;
    d.cycles = info.cycles;
    switch (info.format) {
    case F_NONE: break;
    case F_W: d.ws = u8(fields::ws(w)); break;
    case F_ABS23: d.imm = static_cast<int32_t>((field(next, 6, 0) << 16) | (w & 0xFFFE)); break;
    case F_RETLW:
        d.byte = bit(w, 14);
        d.lit = static_cast<uint16_t>(field(w, 13, 4) & (d.byte ? byte_literal_mask : 0x3FF));
        d.wd = u8(fields::ws(w));
        break;
    case F_REL16: d.imm = relative_target(pc, w); break;
    case F_BRA_COND:
        d.aux = u8(field(w, 19, 16));
        d.imm = relative_target(pc, w);
        break;
    case F_BRA_DSP:
        d.aux = u8(field(w, 17, 16));
        d.imm = relative_target(pc, w);
        break;
    case F_DO_LIT:
    case F_DO_W:
        d.lit = static_cast<uint16_t>(field(w, 13, 0));
        d.ws = u8(fields::ws(w));
        d.imm = static_cast<int32_t>((pc + 4 + 2 * sign_extend(field(next, 15, 0), 16)) & pc_mask);
        break;
    case F_LIT14: d.lit = static_cast<uint16_t>(field(w, 13, 0)); break;
    case F_3OP:
        d.wb = u8(wb_high(w));
        d.byte = bit(w, 14);
        d.dmode = u8(qqq(w));
        d.wd = u8(fields::wd(w));
        d.smode = source_mode_or_literal(w);
        d.ws = u8(fields::ws(w));
        d.lit = static_cast<uint16_t>(field(w, 4, 0));
        break;
    case F_MOV_LIT16:
        d.lit = static_cast<uint16_t>(field(w, 19, 4));
        d.wd = u8(fields::ws(w));
        break;
    case F_MOV:
        d.byte = bit(w, 14);
        d.smode = u8(ppp(w));
        d.ws = u8(fields::ws(w));
        d.dmode = u8(qqq(w));
        d.wd = u8(fields::wd(w));
        d.wb = u8(wb_high(w));
        break;
    case F_MOV_F_W:
        d.lit = static_cast<uint16_t>(field(w, 18, 4) << 1);
        d.wd = u8(fields::ws(w));
        break;
    case F_MOV_W_F:
        d.lit = static_cast<uint16_t>(field(w, 18, 4) << 1);
        d.ws = u8(fields::ws(w));
        break;
    case F_MOV_LDO:
    case F_MOV_STO:
        d.byte = bit(w, 14);
        d.ws = u8(fields::ws(w));
        d.wd = u8(fields::wd(w));
        d.imm = slit10(w) * (d.byte ? 1 : 2);
        break;
    case F_BIT4_WS:
    case F_BIT3_WS:
        d.byte = info.suffix == S_B;
        d.smode = u8(ppp(w));
        d.ws = u8(fields::ws(w));
        d.aux = u8(d.byte ? field(w, 14, 12) : field(w, 15, 12));
        break;
    case F_BIT_WB:
        d.smode = u8(ppp(w));
        d.ws = u8(fields::ws(w));
        d.wb = u8(wb_low(w));
        break;
    case F_BIT3_F:
        d.byte = 1;
        d.lit = static_cast<uint16_t>(field(w, 12, 0));
        d.aux = u8(field(w, 15, 13));
        break;
    case F_LIT10_W:
        d.byte = bit(w, 14);
        d.lit = static_cast<uint16_t>(field(w, 13, 4) & (d.byte ? byte_literal_mask : 0x3FF));
        d.wd = u8(fields::ws(w));
        break;
    case F_MOV_LIT8:
        d.byte = 1;
        d.lit = static_cast<uint16_t>(field(w, 11, 4));
        d.wd = u8(fields::ws(w));
        break;
    case F_FILE:
    case F_FILE_ONLY:
    case F_WREG_F:
    case F_CLR_F:
        d.byte = bit(w, 14);
        d.aux = bit(w, 13);
        d.lit = static_cast<uint16_t>(field(w, 12, 0));
        break;
    case F_MUL:
    case F_MUL_WS:
        d.wb = u8(wb_low(w));
        d.wd = u8(fields::wd(w));
        d.smode = source_mode_or_literal(w);
        d.ws = u8(fields::ws(w));
        d.lit = static_cast<uint16_t>(field(w, 4, 0));
        break;
    case F_TBL:
    case F_WS_WD:
        d.byte = bit(w, 14);
        d.smode = u8(ppp(w));
        d.ws = u8(fields::ws(w));
        d.dmode = u8(qqq(w));
        d.wd = u8(fields::wd(w));
        break;
    case F_MOVD_LOAD:
    case F_WS_WND:
        d.smode = u8(ppp(w));
        d.ws = u8(fields::ws(w));
        d.wd = u8(fields::wd(w));
        break;
    case F_MOVD_STORE:
        d.ws = u8(fields::ws(w));
        d.dmode = u8(qqq(w));
        d.wd = u8(fields::wd(w));
        break;
    case F_MAC:
    case F_MAC_CLR:
    case F_SQR:
    case F_ED:
        d.byte = bit(w, 15);
        if (info.format == F_MAC) {
            d.ws = mac_pairs[field(w, 18, 16)][0];
            d.wb = mac_pairs[field(w, 18, 16)][1];
        } else {
            d.ws = d.wb = u8(prefetch_destination + field(w, 17, 16));
        }
        d.smode = u8(field(w, 9, 6));
        d.dmode = u8(field(w, 5, 2));
        d.wd = u8(prefetch_destination + field(w, 13, 12));
        d.aux = u8(prefetch_destination + field(w, 11, 10));
        d.lit = static_cast<uint16_t>(field(w, 1, 0));
        break;
    case F_SFTAC:
        d.byte = bit(w, 15);
        d.aux = bit(w, 6);
        d.imm = sign_extend(field(w, 5, 0), 6);
        d.ws = u8(fields::ws(w));
        break;
    case F_ACC_WS:
    case F_SAC:
        d.byte = bit(w, 15);
        d.wb = u8(wb_low(w));
        d.imm = sign_extend(field(w, 10, 7), 4);
        d.smode = d.dmode = u8(ppp(w));
        d.ws = d.wd = u8(fields::ws(w));
        break;
    case F_ACC: d.byte = bit(w, 15); break;
    case F_WD:
        d.byte = bit(w, 14);
        d.dmode = u8(qqq(w));
        d.wd = u8(fields::wd(w));
        break;
    case F_DIV:
    case F_DIVF:
        d.wd = u8(fields::wd(w));
        d.wb = u8(wb_low(w));
        d.ws = u8(fields::ws(w));
        break;
    case F_SHIFT:
        d.wb = u8(wb_low(w));
        d.wd = u8(fields::wd(w));
        d.aux = bit(w, 6);
        d.ws = u8(fields::ws(w));
        d.lit = static_cast<uint16_t>(field(w, 3, 0));
        break;
    case F_CP0_WS:
        d.byte = bit(w, 10);
        d.smode = u8(ppp(w));
        d.ws = u8(fields::ws(w));
        break;
    case F_CP_WS:
        d.byte = bit(w, 10);
        d.wb = u8(wb_low(w));
        d.smode = source_mode_or_literal(w);
        d.ws = u8(fields::ws(w));
        d.lit = static_cast<uint16_t>(field(w, 4, 0));
        break;
    case F_CPS:
        d.byte = bit(w, 10);
        d.wb = u8(wb_low(w));
        d.ws = u8(fields::ws(w));
        break;
    case F_PUSHPOP: d.lit = static_cast<uint16_t>(field(w, 15, 0)); break;
    case F_EXCH:
        d.ws = u8(fields::ws(w));
        d.wd = u8(fields::wd(w));
        break;
    case F_PWRSAV: d.lit = static_cast<uint16_t>(field(w, 0, 0)); break;
    }
    return d;
}

} // namespace aseba::dspic30
