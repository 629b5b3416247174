// The disassembler: operands printed per format of the instruction table,
// spelled as pic30-elf-objdump spells them (lower-case hexadecimal with 0x,
// decimal offsets for MOV [W+slit10], branch targets as absolute addresses
// and "." for a branch to itself).

#include "tools/dspic30_sim/disassembler.hpp"

#include "tools/dspic30_sim/isa.hpp"

#include <array>
#include <cinttypes>
#include <cstdio>

namespace aseba::dspic30
{
namespace
{

using namespace fields;

std::string hex(uint64_t value)
{
    char text[24];
    std::snprintf(text, sizeof text, "0x%" PRIx64, value);
    return text;
}

std::string reg(int n)
{
    return "w" + std::to_string(n);
}

// An operand of addressing mode `mode` on register `n`; `wb` is the offset
// register of [Wn+Wb].
std::string operand(int mode, int n, int wb)
{
    const std::string r = reg(n);
    switch (mode) {
    case AM_DIRECT: return r;
    case AM_INDIRECT: return "[" + r + "]";
    case AM_POSTDEC: return "[" + r + "--]";
    case AM_POSTINC: return "[" + r + "++]";
    case AM_PREDEC: return "[--" + r + "]";
    case AM_PREINC: return "[++" + r + "]";
    default: return "[" + r + "+" + reg(wb) + "]";
    }
}

// The Ws operand of the forms where ppp = 11x means #lit5.
std::string source_or_literal(uint32_t w, int wb)
{
    if (ppp(w) >= AM_OFFSET)
        return "#" + hex(field(w, 4, 0));
    return operand(ppp(w), fields::ws(w), wb);
}

// A branch target: objdump computes it in 64 bits and calls a branch to
// itself ".".
std::string target(uint32_t pc, int64_t address)
{
    if (address == static_cast<int64_t>(pc))
        return ".";
    return hex(static_cast<uint64_t>(address));
}

std::string relative(uint32_t pc, uint32_t w)
{
    return target(pc, static_cast<int64_t>(pc) + 2 + 2 * sign_extend(field(w, 15, 0), 16));
}

std::string accumulator(uint32_t w)
{
    return bit(w, 15) ? "B" : "A";
}

const std::array<const char *, 16> condition_names = { "OV",  "C",  "Z",   "N",  "LE", "LT",
                                                       "LEU", "",   "NOV", "NC", "NZ", "NN",
                                                       "GT",  "GE", "GTU", "" };
const std::array<const char *, 4> dsp_condition_names = { "OA", "OB", "SA", "SB" };

// The MAC-class multiplicand pairs by their mmm field (3 and 7 are CLR and
// MOVSAC).
const std::array<const char *, 8> mac_pairs = { "w4 * w5", "w4 * w6", "w4 * w7", "",
                                                "w5 * w6", "w5 * w7", "w6 * w7", "" };

// A prefetch operation: its pointer register (W8/W9 for X, W10/W11 for Y)
// and its post-modification, or the W12 offset.
std::string prefetch(int code, int first_register)
{
    static constexpr std::array<int, 16> modify = { 0, 2, 4, 6, 0, -6, -4, -2,
                                                    0, 2, 4, 6, 0, -6, -4, -2 };
    const int r = first_register + (code >> 3);
    if (code == prefetch_offset)
        return "[" + reg(r) + "+w12]";
    std::string text = "[" + reg(r) + "]";
    if (modify[code] > 0)
        text += "+=" + std::to_string(modify[code]);
    else if (modify[code] < 0)
        text += "-=" + std::to_string(-modify[code]);
    return text;
}

constexpr int x_pointer_base = 8;       // W8, W9
constexpr int y_pointer_base = 10;      // W10, W11
constexpr int prefetch_destination = 4; // W4..W7

void append(std::string &text, const std::string &operand_text)
{
    text += text.empty() ? operand_text : ", " + operand_text;
}

// The prefetch and write-back operands of the MAC class. A prefetch field
// that does nothing is left out; objdump then still prints the destination
// register alone when its field is not W4: in the squaring forms for X and
// Y alike, in the others for Y, or for X when Y has neither.
void mac_operands(std::string &text, uint32_t w, bool squaring, bool write_back)
{
    const int x = static_cast<int>(field(w, 9, 6));
    const int y = static_cast<int>(field(w, 5, 2));
    const int xx = static_cast<int>(field(w, 13, 12));
    const int yy = static_cast<int>(field(w, 11, 10));
    const int awb = static_cast<int>(field(w, 1, 0));
    const std::string xd = reg(prefetch_destination + xx);
    const std::string yd = reg(prefetch_destination + yy);
    if (x != prefetch_none)
        append(text, prefetch(x, x_pointer_base) + ", " + xd);
    else if (squaring && xx != 0)
        append(text, xd);
    if (y != prefetch_none)
        append(text, prefetch(y, y_pointer_base) + ", " + yd);
    else if (yy != 0)
        append(text, yd);
    else if (!squaring && x == prefetch_none && xx != 0)
        append(text, xd);
    if (!write_back)
        return;
    if (awb == 0)
        append(text, "w13");
    else if (awb == 1)
        append(text, "[w13]+=2");
}

std::string operands(Op op, uint32_t pc, uint32_t w, uint32_t next)
{
    const InsnInfo &info = insn_info(op);
    const bool byte = (info.suffix == S_B14 && bit(w, 14)) || (info.suffix == S_B10 && bit(w, 10));
    std::string text;
    switch (info.format) {
    case F_NONE: return "";
    case F_W: return reg(fields::ws(w));
    case F_ABS23: return hex(field(w, 15, 0) | (field(next, 15, 0) << 16));
    case F_RETLW:
        return "#" + hex(field(w, 13, 4) & (byte ? 0xFF : 0x3FF)) + ", " + reg(fields::ws(w));
    case F_REL16: return relative(pc, w);
    case F_BRA_COND: return std::string(condition_names[field(w, 19, 16)]) + ", " + relative(pc, w);
    case F_BRA_DSP:
        return std::string(dsp_condition_names[field(w, 17, 16)]) + ", " + relative(pc, w);
    case F_DO_LIT:
    case F_DO_W: {
        const int64_t end = static_cast<int64_t>(pc) + 4 + 2 * sign_extend(field(next, 15, 0), 16);
        const std::string count =
          info.format == F_DO_LIT ? "#" + hex(field(w, 13, 0)) : reg(fields::ws(w));
        return count + ", " + hex(static_cast<uint64_t>(end));
    }
    case F_LIT14: return "#" + hex(field(w, 13, 0));
    case F_3OP:
        return reg(wb_high(w)) + ", " + source_or_literal(w, 0) + ", " +
               operand(qqq(w), fields::wd(w), 0);
    case F_MOV_LIT16: return "#" + hex(field(w, 19, 4)) + ", " + reg(fields::ws(w));
    case F_MOV:
        return operand(ppp(w), fields::ws(w), wb_high(w)) + ", " +
               operand(qqq(w), fields::wd(w), wb_high(w));
    case F_MOV_F_W: return hex(field(w, 18, 4) << 1) + ", " + reg(fields::ws(w));
    case F_MOV_W_F: return reg(fields::ws(w)) + ", " + hex(field(w, 18, 4) << 1);
    case F_MOV_LDO:
    case F_MOV_STO: {
        const int32_t offset = slit10(w) * (byte ? 1 : 2);
        const std::string sign = offset < 0 ? "-" : "+";
        const std::string base = info.format == F_MOV_LDO ? reg(fields::ws(w)) : reg(fields::wd(w));
        const std::string memory =
          "[" + base + sign + std::to_string(offset < 0 ? -offset : offset) + "]";
        if (info.format == F_MOV_LDO)
            return memory + ", " + reg(fields::wd(w));
        return reg(fields::ws(w)) + ", " + memory;
    }
    case F_BIT4_WS: return operand(ppp(w), fields::ws(w), 0) + ", #" + hex(field(w, 15, 12));
    case F_BIT3_WS:
        // objdump prints bit 15 too (BCLR.B leaves it free)
        return operand(ppp(w), fields::ws(w), 0) + ", #" + hex(field(w, 15, 12));
    case F_BIT_WB: return operand(ppp(w), fields::ws(w), 0) + ", " + reg(wb_low(w));
    case F_BIT3_F: return hex(field(w, 12, 0)) + ", #" + hex(field(w, 15, 13));
    case F_LIT10_W:
        return "#" + hex(field(w, 13, 4) & (byte ? 0xFF : 0x3FF)) + ", " + reg(fields::ws(w));
    case F_MOV_LIT8: return "#" + hex(field(w, 11, 4)) + ", " + reg(fields::ws(w));
    case F_FILE: return hex(field(w, 12, 0)) + (bit(w, 13) ? "" : ", WREG");
    case F_FILE_ONLY: return hex(field(w, 12, 0));
    case F_WREG_F: return "WREG, " + hex(field(w, 12, 0));
    case F_CLR_F: return bit(w, 13) ? hex(field(w, 12, 0)) : "WREG";
    case F_MUL:
    case F_MUL_WS:
        return reg(wb_low(w)) + ", " + source_or_literal(w, 0) + ", " + reg(fields::wd(w));
    case F_TBL:
    case F_WS_WD:
        return operand(ppp(w), fields::ws(w), 0) + ", " + operand(qqq(w), fields::wd(w), 0);
    case F_MOVD_LOAD:
    case F_WS_WND: return operand(ppp(w), fields::ws(w), 0) + ", " + reg(fields::wd(w));
    case F_MOVD_STORE: return reg(fields::ws(w)) + ", " + operand(qqq(w), fields::wd(w), 0);
    case F_MAC:
        text = std::string(mac_pairs[field(w, 18, 16)]) + ", " + accumulator(w);
        mac_operands(text, w, false, op == Op::MAC || op == Op::MSC);
        return text;
    case F_MAC_CLR:
        text = accumulator(w);
        mac_operands(text, w, false, true);
        return text;
    case F_SQR: {
        const std::string r = reg(prefetch_destination + static_cast<int>(field(w, 17, 16)));
        text = r + " * " + r + ", " + accumulator(w);
        mac_operands(text, w, true, false);
        return text;
    }
    case F_ED: {
        const std::string r = reg(prefetch_destination + static_cast<int>(field(w, 17, 16)));
        text = r + " * " + r + ", " + accumulator(w);
        if (field(w, 9, 6) != prefetch_none)
            append(text, prefetch(static_cast<int>(field(w, 9, 6)), x_pointer_base));
        if (field(w, 5, 2) != prefetch_none)
            append(text, prefetch(static_cast<int>(field(w, 5, 2)), y_pointer_base));
        append(text, reg(prefetch_destination + static_cast<int>(field(w, 13, 12))));
        return text;
    }
    case F_SFTAC:
        if (bit(w, 6))
            return accumulator(w) + ", #" + hex(field(w, 5, 0));
        return accumulator(w) + ", " + reg(fields::ws(w));
    case F_ACC_WS:
        return operand(ppp(w), fields::ws(w), wb_low(w)) + ", #" + hex(field(w, 10, 7)) + ", " +
               accumulator(w);
    case F_ACC: return accumulator(w);
    case F_SAC:
        return accumulator(w) + ", #" + hex(field(w, 10, 7)) + ", " +
               operand(ppp(w), fields::ws(w), wb_low(w));
    case F_WD: return operand(qqq(w), fields::wd(w), 0);
    case F_DIV: return reg(fields::wd(w)) + ", " + reg(fields::ws(w));
    case F_DIVF: return reg(wb_low(w)) + ", " + reg(fields::ws(w));
    case F_SHIFT: {
        const std::string amount = bit(w, 6) ? "#" + hex(field(w, 3, 0)) : reg(fields::ws(w));
        return reg(wb_low(w)) + ", " + amount + ", " + reg(fields::wd(w));
    }
    case F_CP0_WS: return operand(ppp(w), fields::ws(w), 0);
    case F_CP_WS: return reg(wb_low(w)) + ", " + source_or_literal(w, 0);
    case F_CPS: return reg(wb_low(w)) + ", " + reg(fields::ws(w));
    case F_PUSHPOP: return hex(field(w, 15, 0));
    case F_EXCH: return reg(fields::ws(w)) + ", " + reg(fields::wd(w));
    case F_PWRSAV: return "#" + hex(field(w, 0, 0));
    }
    return "";
}

std::string mnemonic(Op op, uint32_t w)
{
    const InsnInfo &info = insn_info(op);
    std::string text(info.mnemonic);
    switch (info.suffix) {
    case S_NONE: break;
    case S_W: text += ".w"; break;
    case S_B: text += ".b"; break;
    case S_B14: text += bit(w, 14) ? ".b" : ".w"; break;
    case S_B10: text += bit(w, 10) ? ".b" : ".w"; break;
    }
    return text;
}

} // namespace

std::string disassemble(uint32_t pc, uint32_t word, uint32_t next_word)
{
    const Op op = decode_op(word);
    if (op == Op::INVALID) {
        char text[24];
        std::snprintf(text, sizeof text, ".pword 0x%06" PRIx32, word);
        return text;
    }
    const std::string args = operands(op, pc, word, next_word);
    return args.empty() ? mnemonic(op, word) : mnemonic(op, word) + " " + args;
}

int instruction_words(uint32_t word)
{
    const Op op = decode_op(word);
    return op == Op::INVALID ? 1 : insn_info(op).words;
}

} // namespace aseba::dspic30
