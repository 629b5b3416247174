// The CPU's hot paths, inline in the files that execute instructions: data
// reads and writes that land in RAM (everything else takes the slow path of
// cpu_memory.cpp), and the operand reads and writes of the addressing modes.
// Internal to tools/dspic30_sim.

#pragma once

#include "tools/dspic30_sim/cpu.hpp"

namespace aseba::dspic30
{

// Whether a `size`-byte access at `ea` is an aligned access to RAM.
inline bool ram_access(uint16_t ea, int size)
{
    const uint16_t offset = static_cast<uint16_t>(ea - ram_start);
    return offset < ram_size && (size == 1 || (ea & 1) == 0);
}

[[gnu::always_inline]] inline uint16_t Cpu::read_word(uint16_t ea)
{
    if (ram_access(ea, 2)) {
        const uint16_t i = static_cast<uint16_t>(ea - ram_start);
        return static_cast<uint16_t>(ram_[i] | (ram_[i + 1] << 8));
    }
    return read_slow(ea, false);
}

[[gnu::always_inline]] inline uint8_t Cpu::read_byte(uint16_t ea)
{
    if (ram_access(ea, 1))
        return ram_[static_cast<uint16_t>(ea - ram_start)];
    return static_cast<uint8_t>(read_slow(ea, true));
}

[[gnu::always_inline]] inline void Cpu::write_word(uint16_t ea, uint16_t value)
{
    if (ram_access(ea, 2)) {
        const uint16_t i = static_cast<uint16_t>(ea - ram_start);
        ram_[i] = static_cast<uint8_t>(value);
        ram_[i + 1] = static_cast<uint8_t>(value >> 8);
        return;
    }
    write_slow(ea, value, false);
}

[[gnu::always_inline]] inline void Cpu::write_byte(uint16_t ea, uint8_t value)
{
    if (ram_access(ea, 1)) {
        ram_[static_cast<uint16_t>(ea - ram_start)] = value;
        return;
    }
    write_slow(ea, value, true);
}

// The stack limit check of every W15-based effective address (DS70157
// §4.7.3): below RAM always, above SPLIM once SPLIM has been written.
[[gnu::always_inline]] inline void Cpu::check_stack_ea(uint16_t ea)
{
    if (ea < ram_start || (splim_written_ && ea > splim_))
        stack_error(ea);
}

[[gnu::always_inline]] inline uint16_t Cpu::ea_modify(int mode, int reg, int size, bool write_side)
{
    uint16_t &r = w_[reg];
    const uint16_t old = r;
    uint16_t ea = old;
    uint16_t updated = old;
    switch (mode) {
    case AM_POSTDEC: updated = static_cast<uint16_t>(old - size); break;
    case AM_POSTINC: updated = static_cast<uint16_t>(old + size); break;
    case AM_PREDEC: ea = updated = static_cast<uint16_t>(old - size); break;
    case AM_PREINC: ea = updated = static_cast<uint16_t>(old + size); break;
    default: break;
    }
    if (special_addressing_ && updated != old) {
        updated = modulo_adjust(
          reg, old, updated, write_side && size == 2 && (mode == AM_POSTINC || mode == AM_PREINC));
        if (mode == AM_PREDEC || mode == AM_PREINC)
            ea = updated;
    }
    r = updated;
    if (reg == 15)
        check_stack_ea(ea);
    return ea;
}

[[gnu::always_inline]] inline uint16_t Cpu::read_operand(int mode, int reg, int wb, bool byte)
{
    if (mode == AM_DIRECT)
        return byte ? static_cast<uint16_t>(w_[reg] & 0xFF) : w_[reg];
    uint16_t ea;
    if (mode == AM_OFFSET) {
        ea = static_cast<uint16_t>(w_[reg] + w_[wb]);
        if (reg == 15)
            check_stack_ea(ea);
    } else {
        ea = ea_modify(mode, reg, byte ? 1 : 2, false);
    }
    return byte ? read_byte(ea) : read_word(ea);
}

[[gnu::always_inline]] inline void Cpu::write_operand(int mode,
                                                      int reg,
                                                      int wb,
                                                      bool byte,
                                                      uint16_t value)
{
    if (mode == AM_DIRECT) {
        write_w(reg, value, byte);
        return;
    }
    uint16_t ea;
    if (mode == AM_OFFSET) {
        ea = static_cast<uint16_t>(w_[reg] + w_[wb]);
        if (reg == 15)
            check_stack_ea(ea);
    } else {
        ea = ea_modify(mode, reg, byte ? 1 : 2, true);
    }
    if (byte)
        write_byte(ea, static_cast<uint8_t>(value));
    else
        write_word(ea, value);
}

[[gnu::always_inline]] inline void Cpu::push_word(uint16_t value)
{
    const uint16_t ea = w_[15];
    check_stack_ea(ea);
    write_word(ea, value);
    w_[15] = static_cast<uint16_t>(ea + 2);
}

[[gnu::always_inline]] inline uint16_t Cpu::pop_word()
{
    const uint16_t ea = static_cast<uint16_t>(w_[15] - 2);
    w_[15] = ea;
    check_stack_ea(ea);
    return read_word(ea);
}

} // namespace aseba::dspic30
