// The data space off the RAM fast path: W registers and core SFRs seen as
// memory, peripherals on the SFR bus, PSV, unimplemented addresses, address
// error and stack error detection, and modulo and bit-reversed addressing.

#include "tools/dspic30_sim/cpu_inline.hpp"

#include <cstdio>

namespace aseba::dspic30
{
namespace
{

constexpr uint16_t byte_mask_low = 0x00FF;
constexpr uint16_t word_mask = 0xFFFF;
constexpr uint16_t tblpag_bits = 0x00FF;
constexpr uint16_t count_bits = 0x3FFF;   // RCOUNT, DCOUNT
constexpr uint16_t high_pc_bits = 0x007F; // PC<22:16>
constexpr uint16_t modcon_xmoden = 1u << 15;
constexpr uint16_t modcon_ymoden = 1u << 14;
constexpr uint16_t xbrev_bren = 1u << 15;
constexpr uint16_t xbrev_xb = 0x7FFF;
constexpr int register_field_none = 15; // XWM/YWM/BWM = 15: off
constexpr int acc_upper_shift = 32;
constexpr int64_t acc_sign = int64_t{ 1 } << 39;
constexpr int64_t acc_bits = (int64_t{ 1 } << 40) - 1;

std::string hex16(uint16_t v)
{
    char text[8];
    std::snprintf(text, sizeof text, "0x%04X", v);
    return text;
}

int64_t sign_extend40(int64_t v)
{
    return ((v & acc_bits) ^ acc_sign) - acc_sign;
}

// The bit-reversed addition of XB to the address `value` (the carry runs
// from the most significant bit of the field down, FRM §3.3.2).
uint16_t bit_reversed_add(uint16_t value, uint16_t xb)
{
    // The field spans the bits up to XB's highest set bit, in words.
    int bits = 0;
    while ((xb >> bits) != 0)
        ++bits;
    if (bits == 0)
        return value;
    const uint32_t mask = (1u << bits) - 1;
    auto reverse = [bits](uint32_t v) {
        uint32_t r = 0;
        for (int i = 0; i < bits; ++i)
            if (v & (1u << i))
                r |= 1u << (bits - 1 - i);
        return r;
    };
    const uint32_t index = (value >> 1) & mask;
    const uint32_t next = reverse((reverse(index) + reverse(xb & mask)) & mask);
    return static_cast<uint16_t>((value & ~(mask << 1)) | (next << 1));
}

} // namespace

void Cpu::stack_error(uint16_t ea)
{
    raise_trap(Trap::stack_error,
               "W15-based address " + hex16(ea) +
                 (ea < ram_start ? " below RAM" : " above SPLIM " + hex16(splim_)));
}

uint16_t Cpu::modulo_adjust(int reg, uint16_t old_value, uint16_t new_value, bool bit_reversed)
{
    if (bit_reversed && (xbrev_ & xbrev_bren) && static_cast<int>((modcon_ >> 8) & 0xF) == reg)
        return bit_reversed_add(old_value, xbrev_ & xbrev_xb);
    if ((modcon_ & modcon_xmoden) && static_cast<int>(modcon_ & 0xF) == reg) {
        const uint16_t length = static_cast<uint16_t>(xmodend_ - xmodsrt_ + 1);
        if (new_value > old_value && new_value > xmodend_)
            return static_cast<uint16_t>(new_value - length);
        if (new_value < old_value && new_value < xmodsrt_)
            return static_cast<uint16_t>(new_value + length);
    }
    return new_value;
}

void Cpu::addressing_modes_changed()
{
    const bool x_modulo = (modcon_ & modcon_xmoden) && (modcon_ & 0xF) != register_field_none;
    const bool y_modulo =
      (modcon_ & modcon_ymoden) && ((modcon_ >> 4) & 0xF) != register_field_none;
    const bool reversed = (xbrev_ & xbrev_bren) && ((modcon_ >> 8) & 0xF) != register_field_none;
    special_addressing_ = x_modulo || y_modulo || reversed;
}

uint16_t Cpu::read_slow(uint16_t ea, bool byte)
{
    if (!byte && (ea & 1)) {
        raise_trap(Trap::address_error, "word read at odd address " + hex16(ea));
        return 0;
    }
    if (ea < sfr::WREG_END) {
        const uint16_t v = w_[ea >> 1];
        return byte ? static_cast<uint16_t>((ea & 1) ? v >> 8 : v & byte_mask_low) : v;
    }
    if (ea < sfr_end) {
        const uint16_t v = sfr_read(static_cast<uint16_t>(ea & ~1));
        return byte ? static_cast<uint16_t>((ea & 1) ? v >> 8 : v & byte_mask_low) : v;
    }
    if (ea >= ram_start && ea < ram_end) // a byte read (words took the fast path)
        return ram_[static_cast<uint16_t>(ea - ram_start)];
    if (ea >= psv_window && (corcon_ & corcon::PSV))
        return psv_read(ea, byte);
    raise_trap(Trap::address_error, "read of unimplemented data address " + hex16(ea));
    return 0;
}

void Cpu::write_slow(uint16_t ea, uint16_t value, bool byte)
{
    if (!byte && (ea & 1)) {
        raise_trap(Trap::address_error, "word write at odd address " + hex16(ea));
        return;
    }
    if (ea < sfr::WREG_END) {
        uint16_t &r = w_[ea >> 1];
        if (!byte)
            r = value;
        else if (ea & 1)
            r = static_cast<uint16_t>((r & byte_mask_low) | (value << 8));
        else
            r = static_cast<uint16_t>((r & ~byte_mask_low) | (value & byte_mask_low));
        return;
    }
    if (ea < sfr_end) {
        const uint16_t shift = (byte && (ea & 1)) ? 8 : 0;
        const uint16_t mask = byte ? static_cast<uint16_t>(byte_mask_low << shift) : word_mask;
        sfr_write(static_cast<uint16_t>(ea & ~1), static_cast<uint16_t>(value << shift), mask);
        return;
    }
    if (ea >= ram_start && ea < ram_end) {
        ram_[static_cast<uint16_t>(ea - ram_start)] = static_cast<uint8_t>(value);
        return;
    }
    // Writes to the PSV window and to unimplemented memory change nothing
    // (⚠ the manuals read name no trap for them).
}

uint16_t Cpu::sfr_read(uint16_t address)
{
    if (address < sfr::CORE_END)
        return core_sfr_read(address);
    if (Peripheral *owner = sfr_owner_[address / 2])
        return owner->read(address);
    switch (address) {
    case sfr::NVMCON: return nvmcon_;
    case sfr::NVMADR: return nvmadr_;
    case sfr::NVMADRU: return nvmadru_;
    case sfr::NVMKEY: return 0;
    case sfr::INTCON2: {
        const uint16_t disi = cycles_ < disi_end_ ? intcon2::DISI : 0;
        return static_cast<uint16_t>((sfr_[address / 2] & ~intcon2::DISI) | disi);
    }
    default: return sfr_[address / 2];
    }
}

void Cpu::sfr_write(uint16_t address, uint16_t value, uint16_t mask)
{
    const auto merged = [&](uint16_t old) {
        return static_cast<uint16_t>((old & ~mask) | (value & mask));
    };
    if (address < sfr::CORE_END) {
        core_sfr_write(address, merged(core_sfr_read(address)));
        return;
    }
    if (Peripheral *owner = sfr_owner_[address / 2]) {
        owner->write(address, value, mask);
        return;
    }
    if (address >= sfr::NVMCON && address <= sfr::NVMKEY) {
        nvm_write(address, value, mask);
        return;
    }
    uint16_t &r = sfr_[address / 2];
    r = merged(r);
    if (address >= sfr::INTCON1 && address < sfr::IPC_END)
        recompute_interrupts();
}

uint16_t Cpu::core_sfr_read(uint16_t address)
{
    if (address < sfr::WREG_END)
        return w_[address / 2];
    const auto acc_word = [this](int which, int part) -> uint16_t {
        const int64_t a = acc_[which];
        if (part == 2)
            return static_cast<uint16_t>(
              static_cast<int16_t>(static_cast<int8_t>(a >> acc_upper_shift)));
        return static_cast<uint16_t>(a >> (16 * part));
    };
    switch (address) {
    case sfr::SPLIM: return splim_;
    case sfr::ACCAL: return acc_word(0, 0);
    case sfr::ACCAH: return acc_word(0, 1);
    case sfr::ACCAU: return acc_word(0, 2);
    case sfr::ACCBL: return acc_word(1, 0);
    case sfr::ACCBH: return acc_word(1, 1);
    case sfr::ACCBU: return acc_word(1, 2);
    case sfr::PCL: return static_cast<uint16_t>(current_pc_);
    case sfr::PCH: return static_cast<uint16_t>((current_pc_ >> 16) & high_pc_bits);
    case sfr::TBLPAG: return tblpag_;
    case sfr::PSVPAG: return psvpag_;
    case sfr::RCOUNT: return rcount_;
    case sfr::DCOUNT: return dcount_;
    case sfr::DOSTARTL: return static_cast<uint16_t>(dostart_);
    case sfr::DOSTARTH: return static_cast<uint16_t>((dostart_ >> 16) & high_pc_bits);
    case sfr::DOENDL: return static_cast<uint16_t>(doend_);
    case sfr::DOENDH: return static_cast<uint16_t>((doend_ >> 16) & high_pc_bits);
    case sfr::SR: return sr_;
    case sfr::CORCON: return corcon_;
    case sfr::MODCON: return modcon_;
    case sfr::XMODSRT: return xmodsrt_;
    case sfr::XMODEND: return xmodend_;
    case sfr::YMODSRT: return ymodsrt_;
    case sfr::YMODEND: return ymodend_;
    case sfr::XBREV: return xbrev_;
    case sfr::DISICNT:
        return static_cast<uint16_t>(cycles_ < disi_end_ ? (disi_end_ - cycles_) & count_bits : 0);
    default: return 0;
    }
}

void Cpu::core_sfr_write(uint16_t address, uint16_t value)
{
    if (address < sfr::WREG_END) {
        w_[address / 2] = value;
        return;
    }
    const auto set_acc_word = [this](int which, int part, uint16_t v) {
        int64_t a = acc_[which] & acc_bits;
        const int shift = 16 * part;
        const int64_t field_mask =
          part == 2 ? int64_t{ 0xFF } << shift : int64_t{ 0xFFFF } << shift;
        a = (a & ~field_mask) | ((static_cast<int64_t>(v) << shift) & field_mask);
        acc_[which] = sign_extend40(a);
    };
    switch (address) {
    case sfr::SPLIM:
        splim_ = static_cast<uint16_t>(value & ~1);
        splim_written_ = true;
        break;
    case sfr::ACCAL: set_acc_word(0, 0, value); break;
    case sfr::ACCAH: set_acc_word(0, 1, value); break;
    case sfr::ACCAU: set_acc_word(0, 2, value); break;
    case sfr::ACCBL: set_acc_word(1, 0, value); break;
    case sfr::ACCBH: set_acc_word(1, 1, value); break;
    case sfr::ACCBU: set_acc_word(1, 2, value); break;
    case sfr::TBLPAG: tblpag_ = value & tblpag_bits; break;
    case sfr::PSVPAG: psvpag_ = value & tblpag_bits; break;
    case sfr::RCOUNT: rcount_ = value & count_bits; break;
    case sfr::DCOUNT: dcount_ = value & count_bits; break;
    case sfr::DOSTARTL: dostart_ = (dostart_ & 0x7F0000) | (value & 0xFFFE); break;
    case sfr::DOSTARTH: dostart_ = (dostart_ & 0xFFFF) | ((value & high_pc_bits) << 16); break;
    case sfr::DOENDL:
        doend_ = (doend_ & 0x7F0000) | (value & 0xFFFE);
        if ((sr_ & sr::DA) && !(sr_ & sr::RA))
            watch_pc_ = doend_;
        break;
    case sfr::DOENDH:
        doend_ = (doend_ & 0xFFFF) | ((value & high_pc_bits) << 16);
        if ((sr_ & sr::DA) && !(sr_ & sr::RA))
            watch_pc_ = doend_;
        break;
    case sfr::SR: set_sr(value); break;
    case sfr::CORCON: set_corcon(value); break;
    case sfr::MODCON: modcon_ = value; break;
    case sfr::XMODSRT: xmodsrt_ = static_cast<uint16_t>(value & ~1); break;
    case sfr::XMODEND: xmodend_ = static_cast<uint16_t>(value | 1); break;
    case sfr::YMODSRT: ymodsrt_ = static_cast<uint16_t>(value & ~1); break;
    case sfr::YMODEND: ymodend_ = static_cast<uint16_t>(value | 1); break;
    case sfr::XBREV: xbrev_ = value; break;
    case sfr::DISICNT: disi_end_ = cycles_ + (value & count_bits); break;
    default: break; // PCL, PCH: read-only
    }
    if (address >= sfr::MODCON && address <= sfr::XBREV)
        addressing_modes_changed();
    if (address == sfr::DISICNT)
        recompute_interrupts();
}

void Cpu::set_sr(uint16_t value)
{
    const uint16_t old = sr_;
    constexpr uint16_t flags = sr::C | sr::Z | sr::OV | sr::N | sr::DC;
    const bool ipl_writable = !(sfr_[sfr::INTCON1 / 2] & intcon1::NSTDIS);
    const uint16_t writable = flags | (ipl_writable ? sr::IPL : 0);
    uint16_t next = static_cast<uint16_t>((old & ~writable) | (value & writable));
    // SA and SB can only be cleared, and clearing SAB clears both.
    const uint16_t keep = (value & sr::SAB) ? value : 0;
    next = static_cast<uint16_t>(next & ~(sr::SA | sr::SB));
    next |= old & keep & (sr::SA | sr::SB);
    sr_ = next;
    set_dsp_flags();
    if ((old ^ sr_) & sr::IPL)
        recompute_interrupts();
}

void Cpu::set_corcon(uint16_t value)
{
    const uint16_t old = corcon_;
    uint16_t next = static_cast<uint16_t>((old & ~corcon::WRITABLE) | (value & corcon::WRITABLE));
    if (!(value & corcon::IPL3)) // IPL3 can only be cleared
        next = static_cast<uint16_t>(next & ~corcon::IPL3);
    corcon_ = next;
    if ((value & corcon::EDT) && (sr_ & sr::DA))
        dcount_ = 0; // the loop ends after this iteration
    if ((old ^ corcon_) & corcon::IPL3)
        recompute_interrupts();
}

void Cpu::set_accumulator(int which, int64_t value)
{
    acc_[which] = sign_extend40(value);
}

uint16_t Cpu::read_data(uint16_t address, bool byte)
{
    return byte ? read_byte(address) : read_word(address);
}

void Cpu::write_data(uint16_t address, uint16_t value, bool byte)
{
    if (byte)
        write_byte(address, static_cast<uint8_t>(value));
    else
        write_word(address, value);
}

} // namespace aseba::dspic30
