// Program space from the running program: table reads and writes, PSV
// reads, and the NVM controller that erases and programs flash rows, data
// EEPROM and configuration words after the 0x55/0xAA key sequence
// (hardware fact sheet §1.2-1.5, research notes §9).

#include "tools/dspic30_sim/cpu_inline.hpp"

#include <cstdio>

namespace aseba::dspic30
{
namespace
{

constexpr uint16_t nvmcon_wr = 1u << 15;
constexpr uint16_t nvmcon_wren = 1u << 14;
constexpr uint16_t nvmcon_wrerr = 1u << 13;
constexpr uint16_t nvmcon_writable = nvmcon_wren | nvmcon_wrerr | 0x017F; // TWRI, PROGOP
constexpr uint16_t nvmcon_erase = 1u << 6;
constexpr uint16_t nvmcon_target = 0x0F;
constexpr uint16_t target_flash_row = 0x1;
constexpr uint16_t target_eeprom_word = 0x4;
constexpr uint16_t target_eeprom_row = 0x5;
constexpr uint16_t target_eeprom_all = 0x6;
constexpr uint16_t target_config_word = 0x8;
constexpr uint16_t key_first = 0x55;
constexpr uint16_t key_second = 0xAA;
constexpr uint16_t nvmadru_bits = 0x00FF;
// The WR write must follow the second key closely (⚠ the window is not
// documented; Microchip's sequences put one instruction in between).
constexpr uint64_t unlock_window_cycles = 4;
// About 2 ms per operation, self-timed (⚠ research notes §9).
constexpr uint64_t nvm_operation_cycles = 29491;
constexpr int nvm_irq = 20;
constexpr int psv_extra_cycles = 1; // ⚠ the 30F figure is not confirmed
constexpr uint32_t psv_page_shift = 15;
constexpr uint16_t psv_offset_bits = 0x7FFE;

} // namespace

uint32_t Cpu::table_address(uint16_t ea) const
{
    return (static_cast<uint32_t>(tblpag_) << 16) | ea;
}

uint16_t Cpu::table_read(uint16_t ea, bool high, bool byte)
{
    const uint32_t word = program_.read(table_address(ea));
    if (!high)
        return byte ? static_cast<uint16_t>((ea & 1) ? (word >> 8) & 0xFF : word & 0xFF)
                    : static_cast<uint16_t>(word);
    // The upper byte; its "phantom" neighbour reads 0.
    if (byte && (ea & 1))
        return 0;
    return static_cast<uint16_t>((word >> 16) & 0xFF);
}

void Cpu::table_write(uint16_t ea, bool high, bool byte, uint16_t value)
{
    const uint32_t address = table_address(ea) & ~1u;
    uint32_t index;
    if (ProgramMemory::is_flash(address))
        index = (address / 2) % flash_row_words;
    else if (ProgramMemory::is_eeprom(address))
        index = (address / 2) % eeprom_row_words;
    else if (ProgramMemory::is_config(address))
        index = 0;
    else
        return;
    uint32_t &latch = latches_[index];
    uint32_t bits;
    uint32_t shifted;
    if (!high) {
        bits = byte ? ((ea & 1) ? 0x00FF00u : 0x0000FFu) : 0x00FFFFu;
        shifted = byte && (ea & 1) ? static_cast<uint32_t>(value & 0xFF) << 8 : value;
    } else {
        if (byte && (ea & 1))
            return; // the phantom byte
        bits = 0xFF0000u;
        shifted = static_cast<uint32_t>(value & 0xFF) << 16;
    }
    latch = (latch & ~bits) | (shifted & bits);
    latch_written_[index] = true;
    // A table write also selects the row (what the e-puck's Tiny
    // Bootloader relies on, fact sheet §1.2).
    nvmadr_ = static_cast<uint16_t>(address);
    nvmadru_ = static_cast<uint16_t>((address >> 16) & nvmadru_bits);
}

uint16_t Cpu::psv_read(uint16_t ea, bool byte)
{
    const uint32_t address =
      (static_cast<uint32_t>(psvpag_) << psv_page_shift) | (ea & psv_offset_bits);
    if (!ProgramMemory::is_flash(address) && !ProgramMemory::is_eeprom(address)) {
        char text[64];
        std::snprintf(text,
                      sizeof text,
                      "PSV read of unimplemented program address 0x%06X",
                      static_cast<unsigned>(address));
        raise_trap(Trap::address_error, text);
        return 0;
    }
    cycles_ += psv_extra_cycles;
    const uint32_t word = program_.read(address);
    if (byte)
        return static_cast<uint16_t>((ea & 1) ? (word >> 8) & 0xFF : word & 0xFF);
    return static_cast<uint16_t>(word);
}

void Cpu::nvm_write(uint16_t address, uint16_t value, uint16_t mask)
{
    const auto merged = [&](uint16_t old) {
        return static_cast<uint16_t>((old & ~mask) | (value & mask));
    };
    switch (address) {
    case sfr::NVMKEY: {
        const uint16_t key = static_cast<uint16_t>(value & mask & 0xFF);
        if (key == key_first)
            nvm_key_state_ = 1;
        else if (key == key_second && nvm_key_state_ == 1) {
            nvm_key_state_ = 2;
            nvm_unlocked_until_ = cycles_ + unlock_window_cycles;
        } else
            nvm_key_state_ = 0;
        break;
    }
    case sfr::NVMCON: {
        const uint16_t next = merged(nvmcon_);
        const bool start = (next & nvmcon_wr) && !(nvmcon_ & nvmcon_wr);
        nvmcon_ = static_cast<uint16_t>((nvmcon_ & nvmcon_wr) | (next & nvmcon_writable));
        if (start && nvm_key_state_ == 2 && cycles_ <= nvm_unlocked_until_ &&
            (nvmcon_ & nvmcon_wren))
            nvm_start();
        nvm_key_state_ = 0;
        break;
    }
    case sfr::NVMADR: nvmadr_ = merged(nvmadr_); break;
    case sfr::NVMADRU: nvmadru_ = merged(nvmadru_) & nvmadru_bits; break;
    default: break;
    }
}

void Cpu::invalidate(uint32_t first, uint32_t end)
{
    // The word before may be a GOTO, CALL or DO whose second word changed.
    const uint32_t from = first >= 2 ? first - 2 : 0;
    for (uint32_t pc = from; pc < end && pc < flash_end; pc += 2)
        code_[pc / 2].op = op_undecoded;
}

void Cpu::nvm_start()
{
    const uint32_t address = ((static_cast<uint32_t>(nvmadru_) << 16) | nvmadr_) & ~1u;
    const bool erase = nvmcon_ & nvmcon_erase;
    const uint16_t target = nvmcon_ & nvmcon_target;
    // A power cut at this operation: it reaches the first half of its row
    // (a single word: nothing), then the chip is off.
    const bool cut = ++nvm_operations_ == power_cut_at_;
    const auto done_words = [cut](uint32_t row_words) { return cut ? row_words / 2 : row_words; };
    bool flash_operation = false;
    const auto program_latches = [&](uint32_t row_words) {
        const uint32_t span = 2 * row_words;
        const uint32_t base = address & ~(span - 1);
        for (uint32_t i = 0; i < done_words(row_words); ++i) {
            const uint32_t a = base + 2 * i;
            const uint32_t index = (a / 2) % row_words;
            // Programming only clears bits: an unerased word keeps its zeros.
            program_.program(a, program_.read(a) & latches_[index]);
        }
    };
    if (target == target_flash_row && ProgramMemory::is_flash(address)) {
        flash_operation = true;
        const uint32_t base = address & ~(2 * flash_row_words - 1);
        if (erase)
            program_.erase_row(address, flash_row_words, done_words(flash_row_words));
        else
            program_latches(flash_row_words);
        invalidate(base, base + 2 * flash_row_words);
    } else if (ProgramMemory::is_eeprom(address) &&
               (target == target_eeprom_word || target == target_eeprom_row ||
                target == target_eeprom_all)) {
        if (erase && target == target_eeprom_all)
            program_.erase_row(eeprom_base, eeprom_words, done_words(eeprom_words));
        else if (erase && target == target_eeprom_row)
            program_.erase_row(address, eeprom_row_words, done_words(eeprom_row_words));
        else if (erase && !cut)
            program_.erase_row(address, 1);
        else if (target == target_eeprom_row)
            program_latches(eeprom_row_words);
        else if (!cut)
            program_.program(address,
                             program_.read(address) & latches_[(address / 2) % eeprom_row_words]);
    } else if (target == target_config_word && ProgramMemory::is_config(address) && !erase) {
        if (!cut)
            program_.program(address, latches_[0]);
    } else {
        --nvm_operations_; // refused: no operation began
        nvmcon_ |= nvmcon_wrerr;
        return;
    }
    if (cut) {
        power_cut_ = true;
        request_stop();
        return;
    }
    latches_.fill(erased_word);
    latch_written_.fill(false);
    nvmcon_ |= nvmcon_wr;
    if (flash_operation) {
        // The CPU stalls while the flash is busy: no instruction runs.
        cycles_ += nvm_operation_cycles;
        nvm_finish();
    } else {
        nvm_done_at_ = cycles_ + nvm_operation_cycles;
        next_event_ = 0;
    }
}

void Cpu::nvm_finish()
{
    nvmcon_ = static_cast<uint16_t>(nvmcon_ & ~nvmcon_wr);
    nvm_done_at_ = never;
    raise_interrupt(nvm_irq);
}

} // namespace aseba::dspic30
