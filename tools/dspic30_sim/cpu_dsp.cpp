// The DSP engine: 40-bit accumulators A and B with their saturation modes
// (normal 1.31, super 9.31, or none with catastrophic-overflow detection),
// the 17x17 multiplier in fractional or integer, signed or unsigned mode,
// SAC/SAC.R with convergent or biased rounding and data-write saturation,
// and the MAC class with its X/Y prefetches and accumulator write-back
// (FRM §2.4, research notes §5, DS70157 per instruction).

#include "tools/dspic30_sim/cpu_inline.hpp"

namespace aseba::dspic30
{
namespace
{

constexpr int64_t acc_max = (int64_t{ 1 } << 39) - 1;
constexpr int64_t acc_min = -(int64_t{ 1 } << 39);
constexpr int64_t fraction_max = (int64_t{ 1 } << 31) - 1; // 1.31
constexpr int64_t fraction_min = -(int64_t{ 1 } << 31);
constexpr int64_t acc_bits = (int64_t{ 1 } << 40) - 1;
constexpr int max_shift = 16;          // SFTAC, LAC, SAC shift range
constexpr int word_shift = 16;         // a data word sits in accumulator bits 31:16
constexpr int64_t round_half = 0x8000; // half an LSB of bits 31:16
constexpr int64_t word_max = 0x7FFF;
constexpr int64_t word_min = -0x8000;
constexpr int x_pointer_base = 8;   // W8, W9
constexpr int y_pointer_base = 10;  // W10, W11
constexpr int offset_register = 12; // [W9+W12], [W11+W12]
constexpr int write_back_register = 13;
constexpr uint16_t modcon_ymoden = 1u << 14;
constexpr std::array<int, 8> prefetch_modify = { 0, 2, 4, 6, 0, -6, -4, -2 };

int64_t wrap40(int64_t v)
{
    constexpr int64_t sign = int64_t{ 1 } << 39;
    return ((v & acc_bits) ^ sign) - sign;
}

} // namespace

int64_t Cpu::shift_accumulator(int64_t value, int shift)
{
    // Positive counts shift right (arithmetic), negative ones left.
    if (shift >= 0)
        return value >> shift;
    return static_cast<int64_t>(static_cast<uint64_t>(value) << -shift);
}

int64_t Cpu::multiply(uint16_t a, uint16_t b) const
{
    int64_t product;
    if (corcon_ & corcon::US)
        product = static_cast<int64_t>(a) * b;
    else
        product = static_cast<int64_t>(static_cast<int16_t>(a)) * static_cast<int16_t>(b);
    // Fractional mode: 1.15 x 1.15 gives 2.30, shifted left to 1.31.
    return (corcon_ & corcon::IF) ? product : product * 2;
}

void Cpu::set_dsp_flags()
{
    uint16_t f = static_cast<uint16_t>(sr_ & ~(sr::OAB | sr::SAB));
    if (f & (sr::OA | sr::OB))
        f |= sr::OAB;
    if (f & (sr::SA | sr::SB))
        f |= sr::SAB;
    sr_ = f;
}

void Cpu::store_accumulator(int which, int64_t value)
{
    const bool saturate = corcon_ & (which == 0 ? corcon::SATA : corcon::SATB);
    const bool super = corcon_ & corcon::ACCSAT;
    const uint16_t overflow_flag = which == 0 ? sr::OA : sr::OB;
    const uint16_t saturation_flag = which == 0 ? sr::SA : sr::SB;
    bool saturated = false;
    bool catastrophic = false;
    if (saturate) {
        const int64_t high = super ? acc_max : fraction_max;
        const int64_t low = super ? acc_min : fraction_min;
        if (value > high) {
            value = high;
            saturated = true;
        } else if (value < low) {
            value = low;
            saturated = true;
        }
    } else if (value > acc_max || value < acc_min) {
        catastrophic = true; // bit 39 overflowed
        value = wrap40(value);
    }
    acc_[which] = value;
    const bool overflow = value > fraction_max || value < fraction_min;
    sr_ = static_cast<uint16_t>((sr_ & ~overflow_flag) | (overflow ? overflow_flag : 0));
    if (saturated || catastrophic)
        sr_ |= saturation_flag;
    set_dsp_flags();
    const uint16_t intcon1 = sfr_[sfr::INTCON1 / 2];
    if (overflow && (intcon1 & (which == 0 ? intcon1::OVATE : intcon1::OVBTE)))
        raise_trap(Trap::math_error,
                   which == 0 ? "accumulator A overflow" : "accumulator B overflow");
    if (catastrophic && (intcon1 & intcon1::COVTE))
        raise_trap(Trap::math_error, "catastrophic accumulator overflow");
}

uint16_t Cpu::accumulator_to_word(int64_t value, bool round) const
{
    int64_t high = value >> word_shift;
    if (round) {
        const int64_t low = value & 0xFFFF;
        if (corcon_ & corcon::RND) // biased: add one half
            high += low >= round_half ? 1 : 0;
        else // convergent: a tie goes to the even value
            high += (low > round_half || (low == round_half && (high & 1))) ? 1 : 0;
    }
    if (corcon_ & corcon::SATDW) {
        if (high > word_max)
            high = word_max;
        else if (high < word_min)
            high = word_min;
    }
    return static_cast<uint16_t>(high);
}

void Cpu::mac_prefetch(const Decoded &d,
                       uint16_t &x_value,
                       uint16_t &y_value,
                       bool &has_x,
                       bool &has_y)
{
    has_x = d.smode != prefetch_none;
    has_y = d.dmode != prefetch_none;
    if (has_x) {
        const int r = x_pointer_base + (d.smode >> 3);
        uint16_t ea;
        if (d.smode == prefetch_offset) {
            ea = static_cast<uint16_t>(w_[r] + w_[offset_register]);
        } else {
            ea = w_[r];
            const uint16_t next = static_cast<uint16_t>(ea + prefetch_modify[d.smode & 7]);
            w_[r] = special_addressing_ ? modulo_adjust(r, ea, next, false) : next;
        }
        x_value = read_word(ea);
    }
    if (has_y) {
        const int r = y_pointer_base + (d.dmode >> 3);
        uint16_t ea;
        if (d.dmode == prefetch_offset) {
            ea = static_cast<uint16_t>(w_[r] + w_[offset_register]);
        } else {
            ea = w_[r];
            uint16_t next = static_cast<uint16_t>(ea + prefetch_modify[d.dmode & 7]);
            if ((modcon_ & modcon_ymoden) && static_cast<int>((modcon_ >> 4) & 0xF) == r) {
                const uint16_t length = static_cast<uint16_t>(ymodend_ - ymodsrt_ + 1);
                if (next > ea && next > ymodend_)
                    next = static_cast<uint16_t>(next - length);
                else if (next < ea && next < ymodsrt_)
                    next = static_cast<uint16_t>(next + length);
            }
            w_[r] = next;
        }
        // The Y bus reaches Y RAM only (⚠ other addresses read as 0 here).
        y_value = (ea >= y_ram_start && ea < ram_end) ? read_word(ea) : 0;
    }
}

void Cpu::mac_write_back(const Decoded &d)
{
    constexpr int awb_w13 = 0, awb_w13_indirect = 1;
    const int other = d.byte ? 0 : 1;
    if (d.lit != awb_w13 && d.lit != awb_w13_indirect)
        return;
    const uint16_t v = accumulator_to_word(acc_[other], true); // always rounded
    if (d.lit == awb_w13) {
        w_[write_back_register] = v;
    } else {
        write_word(w_[write_back_register], v);
        w_[write_back_register] = static_cast<uint16_t>(w_[write_back_register] + 2);
    }
}

void Cpu::dsp_instruction(const Decoded &d)
{
    const int which = d.byte;
    const int other = 1 - which;
    switch (d.op) {
    case Op::SFTAC: {
        const int shift = d.aux ? d.imm : static_cast<int16_t>(w_[d.ws]);
        if (shift > max_shift || shift < -max_shift) {
            raise_trap(Trap::math_error, "SFTAC shift out of range");
            return;
        }
        store_accumulator(which, shift_accumulator(acc_[which], shift));
        return;
    }
    case Op::LAC:
    case Op::ADD_ACC_WS: {
        const uint16_t v = read_operand(d.smode, d.ws, d.wb, false);
        const int64_t x =
          shift_accumulator(static_cast<int64_t>(static_cast<int16_t>(v)) << word_shift, d.imm);
        store_accumulator(which, d.op == Op::LAC ? x : acc_[which] + x);
        return;
    }
    case Op::ADD_ACC: store_accumulator(which, acc_[which] + acc_[other]); return;
    case Op::SUB_ACC: store_accumulator(which, acc_[which] - acc_[other]); return;
    case Op::NEG_ACC: store_accumulator(which, -acc_[which]); return;
    case Op::SAC:
    case Op::SAC_R: {
        const uint16_t v =
          accumulator_to_word(shift_accumulator(acc_[which], d.imm), d.op == Op::SAC_R);
        write_operand(d.dmode, d.wd, d.wb, false, v);
        return;
    }
    default: break;
    }

    // The MAC class: multiplicands before the prefetches change W4..W7.
    const uint16_t m = w_[d.ws];
    const uint16_t n = w_[d.wb];
    uint16_t x = 0, y = 0;
    bool has_x, has_y;
    mac_prefetch(d, x, y, has_x, has_y);
    if (d.op != Op::ED && d.op != Op::EDAC && d.op != Op::SQR_MAC && d.op != Op::SQR_MPY)
        mac_write_back(d);
    switch (d.op) {
    case Op::MAC: store_accumulator(which, acc_[which] + multiply(m, n)); break;
    case Op::MSC: store_accumulator(which, acc_[which] - multiply(m, n)); break;
    case Op::MPY: store_accumulator(which, multiply(m, n)); break;
    case Op::MPY_N: store_accumulator(which, -multiply(m, n)); break;
    case Op::SQR_MAC: store_accumulator(which, acc_[which] + multiply(m, m)); break;
    case Op::SQR_MPY: store_accumulator(which, multiply(m, m)); break;
    case Op::ED: store_accumulator(which, multiply(m, m)); break;
    case Op::EDAC: store_accumulator(which, acc_[which] + multiply(m, m)); break;
    case Op::CLR_ACC:
        acc_[which] = 0;
        sr_ = static_cast<uint16_t>(sr_ & ~(which == 0 ? sr::OA | sr::SA : sr::OB | sr::SB));
        set_dsp_flags();
        break;
    default: break; // MOVSAC
    }
    if (d.op == Op::ED || d.op == Op::EDAC) {
        // The difference of the two prefetched values goes to Wxd.
        w_[d.wd] = static_cast<uint16_t>(x - y);
        return;
    }
    if (has_x)
        w_[d.wd] = x;
    if (has_y)
        w_[d.aux] = y;
}

} // namespace aseba::dspic30
