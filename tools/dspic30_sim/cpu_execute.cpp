// The executor: one switch over the operations of instructions.def, run on
// predecoded records, with the ALU's flag rules (DS70157 Section 5 per
// instruction; the "Status Affected" line of each is what the flag helpers
// below write), REPEAT and DO loop bookkeeping after each instruction, and
// the cycle counts of the manual (base count from the table, one more for a
// taken branch, one or two more for a skip).

#include "tools/dspic30_sim/cpu_inline.hpp"

#include <cstdio>

namespace aseba::dspic30
{
namespace
{

constexpr uint16_t count_bits = 0x3FFF;
constexpr uint16_t high_pc_bits = 0x007F;
constexpr int do_levels_max = 7;                // DL<2:0>
constexpr uint16_t stack_pointer_mask = 0xFFFE; // W15<0> is always 0

// Operand widths.
struct Width {
    uint32_t mask;
    uint32_t sign;
    uint32_t half_carry; // the bit DC reports the carry into
};
constexpr Width word_width{ 0xFFFF, 0x8000, 0x0100 };
constexpr Width byte_width{ 0x00FF, 0x0080, 0x0010 };

constexpr const Width &width(bool byte)
{
    return byte ? byte_width : word_width;
}

} // namespace

// Inlined into the dispatch loop: each case names its operation, so the
// helpers' own switches fold away.
#define SIM_INLINE [[gnu::always_inline]] inline

// Flag rules and the small instruction helpers, with access to the CPU.
struct Executor {
    // a + b + carry on the operation's width: C, DC, OV, N, and Z (or, for
    // the multi-precision forms, Z cleared on a non-zero result only).
    SIM_INLINE static uint16_t add(Cpu &c,
                                   uint32_t a,
                                   uint32_t b,
                                   uint32_t carry,
                                   bool byte,
                                   bool sticky_z)
    {
        const Width &wd = width(byte);
        a &= wd.mask;
        b &= wd.mask;
        const uint32_t r = a + b + carry;
        uint16_t f = c.sr_ & static_cast<uint16_t>(~(sr::C | sr::DC | sr::OV | sr::N));
        if (r > wd.mask)
            f |= sr::C;
        if ((a ^ b ^ r) & wd.half_carry)
            f |= sr::DC;
        if (~(a ^ b) & (a ^ r) & wd.sign)
            f |= sr::OV;
        if (r & wd.sign)
            f |= sr::N;
        if ((r & wd.mask) == 0) {
            if (!sticky_z)
                f |= sr::Z;
        } else {
            f = static_cast<uint16_t>(f & ~sr::Z);
        }
        c.sr_ = f;
        return static_cast<uint16_t>(r & wd.mask);
    }

    // a - b - (1 - carry), as a + ~b + carry: C is NOT borrow.
    SIM_INLINE static uint16_t sub(Cpu &c,
                                   uint32_t a,
                                   uint32_t b,
                                   uint32_t carry,
                                   bool byte,
                                   bool sticky_z)
    {
        return add(c, a, ~b & width(byte).mask, carry, byte, sticky_z);
    }

    SIM_INLINE static void set_nz(Cpu &c, uint32_t r, bool byte)
    {
        const Width &wd = width(byte);
        uint16_t f = c.sr_ & static_cast<uint16_t>(~(sr::N | sr::Z));
        if (r & wd.sign)
            f |= sr::N;
        if ((r & wd.mask) == 0)
            f |= sr::Z;
        c.sr_ = f;
    }

    SIM_INLINE static void set_flag(Cpu &c, uint16_t flag, bool value)
    {
        c.sr_ = value ? static_cast<uint16_t>(c.sr_ | flag) : static_cast<uint16_t>(c.sr_ & ~flag);
    }

    SIM_INLINE static uint32_t carry(const Cpu &c)
    {
        return c.sr_ & sr::C;
    }

    SIM_INLINE static bool condition(const Cpu &c, int code)
    {
        const bool C = c.sr_ & sr::C, Z = c.sr_ & sr::Z, N = c.sr_ & sr::N, OV = c.sr_ & sr::OV;
        switch (code) {
        case 0: return OV;
        case 1: return C;
        case 2: return Z;
        case 3: return N;
        case 4: return Z || (N != OV);
        case 5: return N != OV;
        case 6: return !C || Z;
        case 8: return !OV;
        case 9: return !C;
        case 10: return !Z;
        case 11: return !N;
        case 12: return !Z && (N == OV);
        case 13: return N == OV;
        case 14: return C && !Z;
        default: return true;
        }
    }

    // Shifts and rotates by one of the Ws,Wd and f forms.
    SIM_INLINE static uint16_t shift_one(Cpu &c, Op op, uint16_t v, bool byte)
    {
        const Width &wd = width(byte);
        const uint32_t x = v & wd.mask;
        const uint32_t top = wd.sign;
        uint32_t r = 0;
        int out = 0; // the bit shifted out, for C
        bool sets_c = true;
        switch (op) {
        case Op::SL:
        case Op::SL_F:
            r = x << 1;
            out = (x & top) != 0;
            break;
        case Op::LSR:
        case Op::LSR_F:
            r = x >> 1;
            out = x & 1;
            break;
        case Op::ASR:
        case Op::ASR_F:
            r = (x >> 1) | (x & top);
            out = x & 1;
            break;
        case Op::RLC:
        case Op::RLC_F:
            r = (x << 1) | carry(c);
            out = (x & top) != 0;
            break;
        case Op::RRC:
        case Op::RRC_F:
            r = (x >> 1) | (carry(c) ? top : 0);
            out = x & 1;
            break;
        case Op::RLNC:
        case Op::RLNC_F:
            r = (x << 1) | ((x & top) ? 1 : 0);
            sets_c = false;
            break;
        default: // RRNC
            r = (x >> 1) | ((x & 1) ? top : 0);
            sets_c = false;
            break;
        }
        r &= wd.mask;
        if (sets_c)
            set_flag(c, sr::C, out);
        set_nz(c, r, byte);
        return static_cast<uint16_t>(r);
    }

    // The one-operand arithmetic of INC..COM (Ws,Wd and f forms).
    SIM_INLINE static uint16_t unary(Cpu &c, Op op, uint16_t v, bool byte)
    {
        switch (op) {
        case Op::INC:
        case Op::INC_F: return add(c, v, 1, 0, byte, false);
        case Op::INC2:
        case Op::INC2_F: return add(c, v, 2, 0, byte, false);
        case Op::DEC:
        case Op::DEC_F: return sub(c, v, 1, 1, byte, false);
        case Op::DEC2:
        case Op::DEC2_F: return sub(c, v, 2, 1, byte, false);
        case Op::NEG:
        case Op::NEG_F: return sub(c, 0, v, 1, byte, false);
        default: { // COM
            const uint16_t r = static_cast<uint16_t>(~v & width(byte).mask);
            set_nz(c, r, byte);
            return r;
        }
        }
    }

    // The binary operations of the three-operand, literal and f forms:
    // `a` is Wb (or Wn, or f), `b` is Ws (or the literal, or WREG).
    SIM_INLINE static uint16_t binary(Cpu &c, Op op, uint16_t a, uint16_t b, bool byte)
    {
        switch (op) {
        case Op::ADD:
        case Op::ADD_LIT:
        case Op::ADD_F: return add(c, a, b, 0, byte, false);
        case Op::ADDC:
        case Op::ADDC_LIT:
        case Op::ADDC_F: return add(c, a, b, carry(c), byte, true);
        case Op::SUB:
        case Op::SUB_LIT:
        case Op::SUB_F: return sub(c, a, b, 1, byte, false);
        case Op::SUBB:
        case Op::SUBB_LIT:
        case Op::SUBB_F: return sub(c, a, b, carry(c), byte, true);
        case Op::SUBR:
        case Op::SUBR_F: return sub(c, b, a, 1, byte, false);
        case Op::SUBBR:
        case Op::SUBBR_F: return sub(c, b, a, carry(c), byte, true);
        default: break;
        }
        uint16_t r;
        switch (op) {
        case Op::AND:
        case Op::AND_LIT:
        case Op::AND_F: r = a & b; break;
        case Op::XOR:
        case Op::XOR_LIT:
        case Op::XOR_F: r = a ^ b; break;
        default: r = a | b; break; // IOR
        }
        r = static_cast<uint16_t>(r & width(byte).mask);
        set_nz(c, r, byte);
        return r;
    }

    // A read-modify-write on the Ws operand (register or memory), the EA
    // computed once.
    template<typename F>
    static void modify_ws(Cpu &c, const Decoded &d, bool byte, F f)
    {
        if (d.smode == AM_DIRECT) {
            const uint16_t v = byte ? static_cast<uint16_t>(c.w_[d.ws] & 0xFF) : c.w_[d.ws];
            c.write_w(d.ws, f(v), byte);
            return;
        }
        const uint16_t ea = c.ea_modify(d.smode, d.ws, byte ? 1 : 2, false);
        if (byte)
            c.write_byte(ea, static_cast<uint8_t>(f(c.read_byte(ea))));
        else
            c.write_word(ea, f(c.read_word(ea)));
    }

    SIM_INLINE static uint16_t read_ws(Cpu &c, const Decoded &d, bool byte)
    {
        return c.read_operand(d.smode, d.ws, d.wb, byte);
    }

    // The value of an f operand, and where the result of an f{,WREG} form
    // goes.
    SIM_INLINE static uint16_t read_f(Cpu &c, const Decoded &d)
    {
        return d.byte ? c.read_byte(d.lit) : c.read_word(d.lit);
    }
    SIM_INLINE static void write_f_or_wreg(Cpu &c, const Decoded &d, uint16_t value)
    {
        if (!d.aux)
            c.write_w(0, value, d.byte);
        else if (d.byte)
            c.write_byte(d.lit, static_cast<uint8_t>(value));
        else
            c.write_word(d.lit, value);
    }
    SIM_INLINE static uint16_t wreg(const Cpu &c, bool byte)
    {
        return byte ? static_cast<uint16_t>(c.w_[0] & 0xFF) : c.w_[0];
    }

    // The three-operand, literal and f forms of the binary operations.
    template<Op op>
    SIM_INLINE static void three_operand(Cpu &c, const Decoded &d)
    {
        const uint16_t a = d.byte ? static_cast<uint16_t>(c.w_[d.wb] & 0xFF) : c.w_[d.wb];
        const uint16_t b = d.smode == AM_LITERAL ? d.lit : read_ws(c, d, d.byte);
        c.write_operand(d.dmode, d.wd, 0, d.byte, binary(c, op, a, b, d.byte));
    }
    template<Op op>
    SIM_INLINE static void literal_operand(Cpu &c, const Decoded &d)
    {
        const uint16_t a = d.byte ? static_cast<uint16_t>(c.w_[d.wd] & 0xFF) : c.w_[d.wd];
        c.write_w(d.wd, binary(c, op, a, d.lit, d.byte), d.byte);
    }
    template<Op op>
    SIM_INLINE static void file_operand(Cpu &c, const Decoded &d)
    {
        const uint16_t f = read_f(c, d);
        write_f_or_wreg(c, d, binary(c, op, f, wreg(c, d.byte), d.byte));
    }
    template<Op op>
    SIM_INLINE static void unary_ws(Cpu &c, const Decoded &d)
    {
        const uint16_t v = read_ws(c, d, d.byte);
        c.write_operand(d.dmode, d.wd, 0, d.byte, unary(c, op, v, d.byte));
    }
    template<Op op>
    SIM_INLINE static void shift_ws(Cpu &c, const Decoded &d)
    {
        const uint16_t v = read_ws(c, d, d.byte);
        c.write_operand(d.dmode, d.wd, 0, d.byte, shift_one(c, op, v, d.byte));
    }

    static void push_return(Cpu &c, uint32_t return_pc)
    {
        c.push_word(static_cast<uint16_t>(return_pc));
        c.push_word(static_cast<uint16_t>((return_pc >> 16) & high_pc_bits));
    }
    static uint32_t pop_return(Cpu &c)
    {
        const uint16_t high = c.pop_word();
        const uint16_t low = c.pop_word();
        return ((static_cast<uint32_t>(high & high_pc_bits) << 16) | low) & pc_mask;
    }

    // The skip of BTSS/BTSC/CPSxx: the next instruction (one or two words)
    // is fetched and discarded: one or two more cycles.
    static uint32_t skip(Cpu &c, uint32_t next_pc)
    {
        const int words = next_pc < flash_end ? c.instruction_at(next_pc).words : 1;
        c.cycles_ += static_cast<uint64_t>(words);
        return next_pc + 2 * static_cast<uint32_t>(words);
    }

    static void start_do(Cpu &c, const Decoded &d, uint32_t pc, uint16_t count)
    {
        int level = (c.corcon_ & corcon::DL) >> corcon::DL_SHIFT;
        if (level > 0) { // one level of shadows (research notes §6.2)
            c.dcount_shadow_ = c.dcount_;
            c.dostart_shadow_ = c.dostart_;
            c.doend_shadow_ = c.doend_;
        }
        if (level < do_levels_max)
            ++level;
        c.corcon_ = static_cast<uint16_t>((c.corcon_ & ~corcon::DL) | (level << corcon::DL_SHIFT));
        c.dcount_ = count & count_bits;
        c.dostart_ = (pc + 4) & pc_mask;
        c.doend_ = static_cast<uint32_t>(d.imm);
        c.sr_ |= sr::DA;
        c.watch_pc_ = c.doend_;
    }

    static void find_first_one(Cpu &c, const Decoded &d, bool from_left)
    {
        const uint16_t v = read_ws(c, d, false);
        uint16_t result = 0;
        if (v != 0) {
            for (int i = 0; i < 16; ++i) {
                const int b = from_left ? 15 - i : i;
                if (v & (1u << b)) {
                    result = static_cast<uint16_t>(i + 1);
                    break;
                }
            }
        }
        c.w_[d.wd] = result;
        set_flag(c, sr::C, v == 0);
    }

    // FBCL: the shift that normalises Ws, as a negative count (0..-14); -15
    // and C = 1 when all bits equal the sign bit.
    static void find_first_bit_change(Cpu &c, const Decoded &d)
    {
        const uint16_t v = read_ws(c, d, false);
        const int sign = (v >> 15) & 1;
        int count = 0;
        while (count < 15 && ((v >> (14 - count)) & 1) == sign)
            ++count;
        const bool none = count == 15;
        c.w_[d.wd] = static_cast<uint16_t>(-count);
        set_flag(c, sr::C, none);
    }

    static void multiply_w(Cpu &c, const Decoded &d, bool b_signed, bool s_signed)
    {
        const uint16_t a = c.w_[d.wb];
        const uint16_t b = d.smode == AM_LITERAL ? d.lit : read_ws(c, d, false);
        const int64_t x = b_signed ? static_cast<int16_t>(a) : a;
        const int64_t y = s_signed ? static_cast<int16_t>(b) : b;
        const uint32_t product = static_cast<uint32_t>(x * y);
        c.w_[d.wd] = static_cast<uint16_t>(product);
        c.w_[(d.wd + 1) & 15] = static_cast<uint16_t>(product >> 16);
    }

    static void decimal_adjust(Cpu &c, int reg)
    {
        uint32_t v = c.w_[reg] & 0xFF;
        bool carry_out = c.sr_ & sr::C;
        if ((v & 0xF) > 9 || (c.sr_ & sr::DC))
            v += 6;
        if (((v >> 4) & 0x1F) > 9 || carry_out) {
            v += 0x60;
            carry_out = true;
        }
        if (v > 0xFF)
            carry_out = true;
        c.write_w(reg, static_cast<uint16_t>(v), true);
        set_flag(c, sr::C, carry_out);
    }

    static void move_double(Cpu &c, const Decoded &d, bool load)
    {
        if (load) {
            uint16_t low, high;
            if (d.smode == AM_DIRECT) {
                low = c.w_[d.ws];
                high = c.w_[(d.ws + 1) & 15];
            } else {
                const uint16_t ea = c.ea_modify(d.smode, d.ws, 4, false);
                if (d.ws == 15)
                    c.check_stack_ea(static_cast<uint16_t>(ea + 2));
                low = c.read_word(ea);
                high = c.read_word(static_cast<uint16_t>(ea + 2));
            }
            c.w_[d.wd] = low;
            c.w_[(d.wd + 1) & 15] = high;
            return;
        }
        const uint16_t low = c.w_[d.ws];
        const uint16_t high = c.w_[(d.ws + 1) & 15];
        if (d.dmode == AM_DIRECT) {
            c.w_[d.wd] = low;
            c.w_[(d.wd + 1) & 15] = high;
            return;
        }
        const uint16_t ea = c.ea_modify(d.dmode, d.wd, 4, true);
        if (d.wd == 15)
            c.check_stack_ea(static_cast<uint16_t>(ea + 2));
        c.write_word(ea, low);
        c.write_word(static_cast<uint16_t>(ea + 2), high);
    }
};

void Cpu::divide_step(const Decoded &d)
{
    const uint16_t divisor = w_[d.ws];
    if (divisor == 0) {
        raise_trap(Trap::math_error, "divide by zero");
        return;
    }
    // The iterations before the last leave W0, W1 as they were here; the
    // last (RCOUNT = 0, or a DIV outside REPEAT) writes the result, as the
    // 18 steps of the chip's algorithm end with (⚠ the intermediate values
    // of W0, W1 and C are not modelled).
    if ((sr_ & sr::RA) && rcount_ != 0)
        return;
    bool overflow = false;
    uint16_t quotient, remainder;
    bool remainder_negative = false;
    const Op op = d.op;
    if (op == Op::DIV_UW || op == Op::DIV_UD) {
        const uint32_t dividend =
          op == Op::DIV_UW ? w_[d.wd] : (static_cast<uint32_t>(w_[d.wb]) << 16) | w_[d.wd];
        const uint32_t q = dividend / divisor;
        overflow = q > 0xFFFF;
        quotient = static_cast<uint16_t>(q);
        remainder = static_cast<uint16_t>(dividend % divisor);
    } else {
        int32_t dividend;
        if (op == Op::DIV_SW)
            dividend = static_cast<int16_t>(w_[d.wd]);
        else if (op == Op::DIV_SD)
            dividend = static_cast<int32_t>((static_cast<uint32_t>(w_[d.wb]) << 16) | w_[d.wd]);
        else // DIVF: Wm / Wn in 1.15 fractions, so Wm * 2^15 / Wn (⚠ the manual's
             // "Wm -> W1, 0 -> W0" taken literally would overflow every quotient)
            dividend = static_cast<int32_t>(static_cast<int16_t>(w_[d.wb])) * 32768;
        const int32_t s = static_cast<int16_t>(divisor);
        const int64_t q = static_cast<int64_t>(dividend) / s;
        const int64_t r = static_cast<int64_t>(dividend) % s;
        overflow = q > INT16_MAX || q < INT16_MIN;
        if (op == Op::DIVF)
            overflow = overflow || std::abs(static_cast<int16_t>(w_[d.wb])) >= std::abs(s);
        quotient = static_cast<uint16_t>(q);
        remainder = static_cast<uint16_t>(r);
        remainder_negative = r < 0;
    }
    w_[0] = quotient;
    w_[1] = remainder;
    Executor::set_flag(*this, sr::N, remainder_negative);
    Executor::set_flag(*this, sr::OV, overflow);
    Executor::set_flag(*this, sr::Z, remainder == 0);
}

void Cpu::loop_end(uint32_t pc)
{
    if ((sr_ & sr::RA) && pc == repeat_pc_) {
        if (rcount_ == 0) {
            sr_ = static_cast<uint16_t>(sr_ & ~sr::RA);
            watch_pc_ = (sr_ & sr::DA) ? doend_ : no_watch;
        } else {
            --rcount_;
            pc_ = pc;
        }
        return;
    }
    if (!(sr_ & sr::DA) || pc != doend_)
        return;
    if (dcount_ != 0) {
        --dcount_;
        pc_ = dostart_;
        return;
    }
    // The loop ends: back to the outer loop's registers, if any.
    int level = (corcon_ & corcon::DL) >> corcon::DL_SHIFT;
    if (level > 0)
        --level;
    corcon_ = static_cast<uint16_t>((corcon_ & ~corcon::DL) | (level << corcon::DL_SHIFT));
    if (level > 0) {
        dcount_ = dcount_shadow_;
        dostart_ = dostart_shadow_;
        doend_ = doend_shadow_;
        watch_pc_ = doend_;
    } else {
        sr_ = static_cast<uint16_t>(sr_ & ~sr::DA);
        watch_pc_ = no_watch;
    }
}

const Decoded &Cpu::instruction_at(uint32_t pc)
{
    Decoded &d = code_[(pc & pc_mask) / 2];
    if (d.op == op_undecoded) {
        const uint32_t *flash = program_.flash();
        const uint32_t index = (pc & pc_mask) / 2;
        const uint32_t next = index + 1 < flash_words ? flash[index + 1] : 0;
        d = predecode(pc & pc_mask, flash[index], next);
    }
    return d;
}

StopReason Cpu::run(uint64_t cycle_limit)
{
    next_event_ = 0;
    return trace_ ? run_loop<true>(cycle_limit) : run_loop<false>(cycle_limit);
}

void Cpu::request_stop()
{
    stop_requested_ = true;
    next_event_ = 0;
}

template<bool traced>
StopReason Cpu::run_loop(uint64_t cycle_limit)
{
    using E = Executor;
    StopReason reason = StopReason::cycle_limit;
    for (;;) {
        if (cycles_ >= next_event_) {
            if (!service(cycle_limit, reason))
                return reason;
            if (sleeping_)
                continue;
        }
        const uint32_t pc = pc_;
        current_pc_ = pc;
        if (pc >= flash_end) {
            char text[80];
            std::snprintf(text,
                          sizeof text,
                          "instruction fetch at 0x%06X, outside program flash",
                          static_cast<unsigned>(pc));
            raise_trap(Trap::address_error, text);
            cycles_ += 1;
            continue;
        }
        const Decoded &d = code_[pc / 2].op != op_undecoded ? code_[pc / 2] : instruction_at(pc);
        if constexpr (traced)
            trace_(*this);
        history_[instructions_++ % history_length] = pc;
        cycles_ += d.cycles;
        uint32_t npc = pc + 2 * d.words;
        switch (d.op) {
        // --- program flow ----------------------------------------------------
        case Op::NOP:
        case Op::NOPR:
        case Op::BREAK: break;
        case Op::BRA_W:
            npc = (pc + 2 + 2 * static_cast<uint32_t>(static_cast<int16_t>(w_[d.ws]))) & pc_mask;
            break;
        case Op::GOTO_W: npc = w_[d.ws] & 0xFFFEu; break;
        case Op::RCALL_W:
            E::push_return(*this, npc);
            npc = (pc + 2 + 2 * static_cast<uint32_t>(static_cast<int16_t>(w_[d.ws]))) & pc_mask;
            break;
        case Op::CALL_W:
            E::push_return(*this, npc);
            npc = w_[d.ws] & 0xFFFEu;
            break;
        case Op::CALL:
            E::push_return(*this, npc);
            npc = static_cast<uint32_t>(d.imm);
            break;
        case Op::GOTO: npc = static_cast<uint32_t>(d.imm); break;
        case Op::RETLW:
            write_w(d.wd, d.lit, d.byte);
            npc = E::pop_return(*this);
            break;
        case Op::RETURN: npc = E::pop_return(*this); break;
        case Op::RETFIE:
            return_from_interrupt();
            npc = pc_;
            break;
        case Op::RCALL:
            E::push_return(*this, npc);
            npc = static_cast<uint32_t>(d.imm);
            break;
        case Op::DO_LIT: E::start_do(*this, d, pc, d.lit); break;
        case Op::DO_W: E::start_do(*this, d, pc, w_[d.ws]); break;
        case Op::REPEAT_LIT:
        case Op::REPEAT_W:
            rcount_ = (d.op == Op::REPEAT_LIT ? d.lit : w_[d.ws]) & count_bits;
            if (rcount_ != 0) {
                sr_ |= sr::RA;
                repeat_pc_ = npc;
                watch_pc_ = npc;
            }
            break;
        case Op::BRA_DSP:
            if (sr_ & (sr::OA >> d.aux)) {
                npc = static_cast<uint32_t>(d.imm);
                cycles_ += 1;
            }
            break;
        case Op::BRA: npc = static_cast<uint32_t>(d.imm); break;
        case Op::BRA_COND:
            if (E::condition(*this, d.aux)) {
                npc = static_cast<uint32_t>(d.imm);
                cycles_ += 1;
            }
            break;

        // --- three-operand arithmetic and logic ------------------------------
        case Op::SUBR: E::three_operand<Op::SUBR>(*this, d); break;
        case Op::SUBBR: E::three_operand<Op::SUBBR>(*this, d); break;
        case Op::ADD: E::three_operand<Op::ADD>(*this, d); break;
        case Op::ADDC: E::three_operand<Op::ADDC>(*this, d); break;
        case Op::SUB: E::three_operand<Op::SUB>(*this, d); break;
        case Op::SUBB: E::three_operand<Op::SUBB>(*this, d); break;
        case Op::AND: E::three_operand<Op::AND>(*this, d); break;
        case Op::XOR: E::three_operand<Op::XOR>(*this, d); break;
        case Op::IOR: E::three_operand<Op::IOR>(*this, d); break;

        // --- moves -----------------------------------------------------------
        case Op::MOV_LIT16: w_[d.wd] = d.lit; break;
        case Op::MOV: {
            const uint16_t v = read_operand(d.smode, d.ws, d.wb, d.byte);
            write_operand(d.dmode, d.wd, d.wb, d.byte, v);
            break;
        }
        case Op::MOV_F_W: w_[d.wd] = read_word(d.lit); break;
        case Op::MOV_W_F: write_word(d.lit, w_[d.ws]); break;
        case Op::MOV_LDO: {
            const uint16_t ea = static_cast<uint16_t>(w_[d.ws] + d.imm);
            if (d.ws == 15)
                check_stack_ea(ea);
            write_w(d.wd, d.byte ? read_byte(ea) : read_word(ea), d.byte);
            break;
        }
        case Op::MOV_STO: {
            const uint16_t ea = static_cast<uint16_t>(w_[d.wd] + d.imm);
            if (d.wd == 15)
                check_stack_ea(ea);
            if (d.byte)
                write_byte(ea, static_cast<uint8_t>(w_[d.ws]));
            else
                write_word(ea, w_[d.ws]);
            break;
        }
        case Op::MOV_LIT8: write_w(d.wd, d.lit, true); break;
        case Op::MOV_LIT10: w_[d.wd] = d.lit; break;
        case Op::MOV_WREG_F:
            if (d.byte)
                write_byte(d.lit, static_cast<uint8_t>(w_[0]));
            else
                write_word(d.lit, w_[0]);
            break;
        case Op::MOV_F: {
            const uint16_t v = E::read_f(*this, d);
            E::set_nz(*this, v, d.byte);
            E::write_f_or_wreg(*this, d, v);
            break;
        }
        case Op::MOVD_LOAD: E::move_double(*this, d, true); break;
        case Op::MOVD_STORE: E::move_double(*this, d, false); break;
        case Op::EXCH: std::swap(w_[d.ws], w_[d.wd]); break;
        case Op::SWAP_W: w_[d.ws] = static_cast<uint16_t>((w_[d.ws] << 8) | (w_[d.ws] >> 8)); break;
        case Op::SWAP_B: {
            const uint16_t v = w_[d.ws];
            w_[d.ws] = static_cast<uint16_t>((v & 0xFF00) | ((v << 4) & 0xF0) | ((v >> 4) & 0x0F));
            break;
        }
        case Op::SE: {
            const uint16_t v =
              static_cast<uint16_t>(static_cast<int8_t>(E::read_ws(*this, d, true)));
            w_[d.wd] = v;
            E::set_nz(*this, v, false);
            E::set_flag(*this, sr::C, !(v & 0x8000));
            break;
        }
        case Op::ZE: {
            const uint16_t v = E::read_ws(*this, d, true);
            w_[d.wd] = v;
            E::set_nz(*this, v, false);
            E::set_flag(*this, sr::C, true);
            break;
        }

        // --- bit operations --------------------------------------------------
        case Op::BSET_W:
        case Op::BSET_B:
            E::modify_ws(*this, d, d.byte, [&](uint16_t v) {
                return static_cast<uint16_t>(v | (1u << d.aux));
            });
            break;
        case Op::BCLR_W:
        case Op::BCLR_B:
            E::modify_ws(*this, d, d.byte, [&](uint16_t v) {
                return static_cast<uint16_t>(v & ~(1u << d.aux));
            });
            break;
        case Op::BTG_W:
        case Op::BTG_B:
            E::modify_ws(*this, d, d.byte, [&](uint16_t v) {
                return static_cast<uint16_t>(v ^ (1u << d.aux));
            });
            break;
        case Op::BTST_C:
        case Op::BTST_Z:
        case Op::BTST_CW:
        case Op::BTST_ZW: {
            const int b = (d.op == Op::BTST_CW || d.op == Op::BTST_ZW) ? (w_[d.wb] & 0xF) : d.aux;
            const bool set = (E::read_ws(*this, d, false) >> b) & 1;
            if (d.op == Op::BTST_C || d.op == Op::BTST_CW)
                E::set_flag(*this, sr::C, set);
            else
                E::set_flag(*this, sr::Z, !set);
            break;
        }
        case Op::BTSTS_C:
        case Op::BTSTS_Z:
            E::modify_ws(*this, d, false, [&](uint16_t v) {
                const bool set = (v >> d.aux) & 1;
                if (d.op == Op::BTSTS_C)
                    E::set_flag(*this, sr::C, set);
                else
                    E::set_flag(*this, sr::Z, !set);
                return static_cast<uint16_t>(v | (1u << d.aux));
            });
            break;
        case Op::BSW_C:
        case Op::BSW_Z: {
            const int b = w_[d.wb] & 0xF;
            const bool value = d.op == Op::BSW_C ? (sr_ & sr::C) != 0 : !(sr_ & sr::Z);
            E::modify_ws(*this, d, false, [&](uint16_t v) {
                return static_cast<uint16_t>(value ? v | (1u << b) : v & ~(1u << b));
            });
            break;
        }
        case Op::BTSS_W:
        case Op::BTSC_W: {
            const bool set = (E::read_ws(*this, d, false) >> d.aux) & 1;
            if (set == (d.op == Op::BTSS_W))
                npc = E::skip(*this, npc);
            break;
        }
        case Op::BSET_F:
            write_byte(d.lit, static_cast<uint8_t>(read_byte(d.lit) | (1u << d.aux)));
            break;
        case Op::BCLR_F:
            write_byte(d.lit, static_cast<uint8_t>(read_byte(d.lit) & ~(1u << d.aux)));
            break;
        case Op::BTG_F:
            write_byte(d.lit, static_cast<uint8_t>(read_byte(d.lit) ^ (1u << d.aux)));
            break;
        case Op::BTST_F: E::set_flag(*this, sr::Z, !((read_byte(d.lit) >> d.aux) & 1)); break;
        case Op::BTSTS_F: {
            const uint8_t v = read_byte(d.lit);
            E::set_flag(*this, sr::Z, !((v >> d.aux) & 1));
            write_byte(d.lit, static_cast<uint8_t>(v | (1u << d.aux)));
            break;
        }
        case Op::BTSS_F:
        case Op::BTSC_F: {
            const bool set = (read_byte(d.lit) >> d.aux) & 1;
            if (set == (d.op == Op::BTSS_F))
                npc = E::skip(*this, npc);
            break;
        }

        // --- literal and file-register arithmetic ----------------------------
        case Op::ADD_LIT: E::literal_operand<Op::ADD_LIT>(*this, d); break;
        case Op::ADDC_LIT: E::literal_operand<Op::ADDC_LIT>(*this, d); break;
        case Op::SUB_LIT: E::literal_operand<Op::SUB_LIT>(*this, d); break;
        case Op::SUBB_LIT: E::literal_operand<Op::SUBB_LIT>(*this, d); break;
        case Op::AND_LIT: E::literal_operand<Op::AND_LIT>(*this, d); break;
        case Op::XOR_LIT: E::literal_operand<Op::XOR_LIT>(*this, d); break;
        case Op::IOR_LIT: E::literal_operand<Op::IOR_LIT>(*this, d); break;
        case Op::ADD_F: E::file_operand<Op::ADD_F>(*this, d); break;
        case Op::ADDC_F: E::file_operand<Op::ADDC_F>(*this, d); break;
        case Op::SUB_F: E::file_operand<Op::SUB_F>(*this, d); break;
        case Op::SUBB_F: E::file_operand<Op::SUBB_F>(*this, d); break;
        case Op::AND_F: E::file_operand<Op::AND_F>(*this, d); break;
        case Op::XOR_F: E::file_operand<Op::XOR_F>(*this, d); break;
        case Op::IOR_F: E::file_operand<Op::IOR_F>(*this, d); break;
        case Op::SUBR_F: E::file_operand<Op::SUBR_F>(*this, d); break;
        case Op::SUBBR_F: E::file_operand<Op::SUBBR_F>(*this, d); break;
        case Op::INC_F:
        case Op::INC2_F:
        case Op::DEC_F:
        case Op::DEC2_F:
        case Op::NEG_F:
        case Op::COM_F:
            E::write_f_or_wreg(*this, d, E::unary(*this, d.op, E::read_f(*this, d), d.byte));
            break;
        case Op::CLR_F: E::write_f_or_wreg(*this, d, 0); break;
        case Op::SETM_F: E::write_f_or_wreg(*this, d, 0xFFFF); break;
        case Op::SL_F:
        case Op::LSR_F:
        case Op::ASR_F:
        case Op::RLNC_F:
        case Op::RLC_F:
        case Op::RRNC_F:
        case Op::RRC_F:
            E::write_f_or_wreg(*this, d, E::shift_one(*this, d.op, E::read_f(*this, d), d.byte));
            break;
        case Op::MUL_F:
            if (d.byte) {
                w_[2] = static_cast<uint16_t>((read_byte(d.lit) & 0xFF) * (w_[0] & 0xFF));
            } else {
                const uint32_t p = static_cast<uint32_t>(read_word(d.lit)) * w_[0];
                w_[2] = static_cast<uint16_t>(p);
                w_[3] = static_cast<uint16_t>(p >> 16);
            }
            break;
        case Op::MUL_UU: E::multiply_w(*this, d, false, false); break;
        case Op::MUL_US: E::multiply_w(*this, d, false, true); break;
        case Op::MUL_SU: E::multiply_w(*this, d, true, false); break;
        case Op::MUL_SS: E::multiply_w(*this, d, true, true); break;

        // --- table access ----------------------------------------------------
        case Op::TBLRDL:
        case Op::TBLRDH: {
            const uint16_t ea =
              d.smode == AM_DIRECT ? w_[d.ws] : ea_modify(d.smode, d.ws, d.byte ? 1 : 2, false);
            write_operand(d.dmode, d.wd, 0, d.byte, table_read(ea, d.op == Op::TBLRDH, d.byte));
            break;
        }
        case Op::TBLWTL:
        case Op::TBLWTH: {
            const uint16_t v = E::read_ws(*this, d, d.byte);
            const uint16_t ea =
              d.dmode == AM_DIRECT ? w_[d.wd] : ea_modify(d.dmode, d.wd, d.byte ? 1 : 2, true);
            table_write(ea, d.op == Op::TBLWTH, d.byte, v);
            break;
        }

        // --- shifts and rotates ----------------------------------------------
        case Op::SL: E::shift_ws<Op::SL>(*this, d); break;
        case Op::LSR: E::shift_ws<Op::LSR>(*this, d); break;
        case Op::ASR: E::shift_ws<Op::ASR>(*this, d); break;
        case Op::RLNC: E::shift_ws<Op::RLNC>(*this, d); break;
        case Op::RLC: E::shift_ws<Op::RLC>(*this, d); break;
        case Op::RRNC: E::shift_ws<Op::RRNC>(*this, d); break;
        case Op::RRC: E::shift_ws<Op::RRC>(*this, d); break;
        case Op::SL_SHIFT:
        case Op::LSR_SHIFT:
        case Op::ASR_SHIFT: {
            const int amount = d.aux ? d.lit : (w_[d.ws] & 0xF);
            const uint16_t v = w_[d.wb];
            uint16_t r;
            if (d.op == Op::SL_SHIFT)
                r = static_cast<uint16_t>(v << amount);
            else if (d.op == Op::LSR_SHIFT)
                r = static_cast<uint16_t>(v >> amount);
            else
                r = static_cast<uint16_t>(static_cast<int16_t>(v) >> amount);
            w_[d.wd] = r;
            E::set_nz(*this, r, false);
            break;
        }
        case Op::FF1R: E::find_first_one(*this, d, false); break;
        case Op::FF1L: E::find_first_one(*this, d, true); break;
        case Op::FBCL: E::find_first_bit_change(*this, d); break;
        case Op::DIV_SW:
        case Op::DIV_SD:
        case Op::DIV_UW:
        case Op::DIV_UD:
        case Op::DIVF: divide_step(d); break;

        // --- compares ----------------------------------------------------------
        case Op::CP0_WS: E::sub(*this, E::read_ws(*this, d, d.byte), 0, 1, d.byte, false); break;
        case Op::CP_WS:
        case Op::CPB_WS: {
            const uint16_t a = d.byte ? static_cast<uint16_t>(w_[d.wb] & 0xFF) : w_[d.wb];
            const uint16_t b = d.smode == AM_LITERAL ? d.lit : E::read_ws(*this, d, d.byte);
            if (d.op == Op::CP_WS)
                E::sub(*this, a, b, 1, d.byte, false);
            else
                E::sub(*this, a, b, E::carry(*this), d.byte, true);
            break;
        }
        case Op::CP0_F: E::sub(*this, E::read_f(*this, d), 0, 1, d.byte, false); break;
        case Op::CP_F:
            E::sub(*this, E::read_f(*this, d), E::wreg(*this, d.byte), 1, d.byte, false);
            break;
        case Op::CPB_F:
            E::sub(
              *this, E::read_f(*this, d), E::wreg(*this, d.byte), E::carry(*this), d.byte, true);
            break;
        case Op::CPSGT:
        case Op::CPSLT:
        case Op::CPSNE:
        case Op::CPSEQ: {
            int32_t a = w_[d.wb], b = w_[d.ws];
            if (d.byte) {
                a = static_cast<int8_t>(a);
                b = static_cast<int8_t>(b);
            } else {
                a = static_cast<int16_t>(a);
                b = static_cast<int16_t>(b);
            }
            bool taken;
            switch (d.op) {
            case Op::CPSGT: taken = a > b; break;
            case Op::CPSLT: taken = a < b; break;
            case Op::CPSNE: taken = a != b; break;
            default: taken = a == b; break;
            }
            if (taken)
                npc = E::skip(*this, npc);
            break;
        }

        // --- one-operand arithmetic -----------------------------------------------
        case Op::INC: E::unary_ws<Op::INC>(*this, d); break;
        case Op::INC2: E::unary_ws<Op::INC2>(*this, d); break;
        case Op::DEC: E::unary_ws<Op::DEC>(*this, d); break;
        case Op::DEC2: E::unary_ws<Op::DEC2>(*this, d); break;
        case Op::NEG: E::unary_ws<Op::NEG>(*this, d); break;
        case Op::COM: E::unary_ws<Op::COM>(*this, d); break;
        case Op::CLR: write_operand(d.dmode, d.wd, 0, d.byte, 0); break;
        case Op::SETM: write_operand(d.dmode, d.wd, 0, d.byte, 0xFFFF); break;
        case Op::DAW_B: E::decimal_adjust(*this, d.ws); break;

        // --- DSP engine ------------------------------------------------------------
        case Op::CLR_ACC:
        case Op::MOVSAC:
        case Op::MPY:
        case Op::MPY_N:
        case Op::MAC:
        case Op::MSC:
        case Op::SFTAC:
        case Op::ADD_ACC_WS:
        case Op::LAC:
        case Op::ADD_ACC:
        case Op::NEG_ACC:
        case Op::SUB_ACC:
        case Op::SAC:
        case Op::SAC_R:
        case Op::SQR_MAC:
        case Op::SQR_MPY:
        case Op::EDAC:
        case Op::ED: dsp_instruction(d); break;

        // --- stack and control ------------------------------------------------------
        case Op::PUSH_F: push_word(read_word(d.lit)); break;
        case Op::POP_F: write_word(d.lit, pop_word()); break;
        case Op::LNK:
            push_word(w_[14]);
            w_[14] = w_[15];
            w_[15] = static_cast<uint16_t>(w_[15] + d.lit);
            break;
        case Op::ULNK:
            w_[15] = w_[14];
            w_[14] = pop_word();
            break;
        case Op::DISI:
            disi_end_ = cycles_ + d.lit + 1;
            recompute_interrupts();
            break;
        case Op::RESET:
            device_reset(rcon::SWR);
            npc = pc_;
            break;
        case Op::PWRSAV:
            sfr_[sfr::RCON / 2] |= d.lit ? rcon::IDLE : rcon::SLEEP;
            sleeping_ = true;
            next_event_ = 0;
            break;
        case Op::CLRWDT: restart_watchdog(); break;
        case Op::PUSH_S:
            for (int i = 0; i < 4; ++i)
                w_shadow_[i] = w_[i];
            sr_shadow_ = sr_ & sr::ALU_FLAGS;
            break;
        case Op::POP_S:
            for (int i = 0; i < 4; ++i)
                w_[i] = w_shadow_[i];
            sr_ = static_cast<uint16_t>((sr_ & ~sr::ALU_FLAGS) | sr_shadow_);
            break;

        case Op::INVALID:
        default:
            if (stop_on_illegal_) {
                cycles_ -= d.cycles;
                illegal_seen_ = true;
                return StopReason::illegal_instruction;
            }
            break;
        }
        // W15<0> reads 0 whatever was written to it (FRM2 p.2-8): one AND
        // here rather than a test at each of the many places W15 is written.
        w_[stack_pointer_register] &= stack_pointer_mask;
        pc_ = npc;
        if (pc == watch_pc_)
            loop_end(pc);
    }
}

template StopReason Cpu::run_loop<true>(uint64_t);
template StopReason Cpu::run_loop<false>(uint64_t);

} // namespace aseba::dspic30
