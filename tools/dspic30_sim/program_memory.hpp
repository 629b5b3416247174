// The dsPIC30F6014A's program space: 48 K words of flash, the data EEPROM,
// the configuration words and the device ID, as table reads, PSV and the
// loader see them (hardware fact sheet §1.1-1.5). Writes from the running
// program go through the NVM controller (cpu_nvm.cpp), which erases and
// programs whole rows here.

#pragma once

#include "tools/dspic30_sim/memory_map.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace aseba::dspic30
{

class ProgramMemory
{
  public:
    // Erased flash and EEPROM, erased configuration words.
    ProgramMemory();

    // The 24-bit word at PC address `address` (bit 0 ignored); 0 where
    // nothing is implemented (⚠ what the chip returns there is not
    // documented).
    uint32_t read(uint32_t address) const;

    // Whether `address` is in flash, in the data EEPROM, in the
    // configuration words.
    static bool is_flash(uint32_t address)
    {
        return address < flash_end;
    }
    static bool is_eeprom(uint32_t address)
    {
        return address >= eeprom_base && address < eeprom_end;
    }
    static bool is_config(uint32_t address)
    {
        return address >= config_base && address < config_end;
    }

    // Sets the word at `address` as a programmer would (flash: 24 bits;
    // EEPROM and configuration: 16 bits). Returns false where nothing can
    // be stored.
    bool program(uint32_t address, uint32_t word);

    // Erases the row of `row_words` words holding `address` (flash or
    // EEPROM): its first `done_words` words (all by default; fewer for a
    // power cut midway).
    void erase_row(uint32_t address, uint32_t row_words, uint32_t done_words = ~0u);

    // The flash words, for the executor's fetch (index = PC / 2).
    const uint32_t *flash() const
    {
        return flash_.data();
    }

  private:
    std::vector<uint32_t> flash_;
    std::vector<uint16_t> eeprom_;
    std::array<uint16_t, config_words> config_;
};

} // namespace aseba::dspic30
