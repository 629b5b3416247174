// Program space storage. The EEPROM and configuration words hold 16 bits;
// a table read of their upper byte gives 0.

#include "tools/dspic30_sim/program_memory.hpp"

#include <algorithm>

namespace aseba::dspic30
{
namespace
{
constexpr uint16_t erased_data_word = 0xFFFF;
constexpr uint32_t word_bits = 0xFFFFFF;
} // namespace

ProgramMemory::ProgramMemory()
  : flash_(flash_words, erased_word)
  , eeprom_(eeprom_words, erased_data_word)
{
    config_.fill(erased_data_word);
}

uint32_t ProgramMemory::read(uint32_t address) const
{
    const uint32_t a = address & ~1u;
    if (is_flash(a))
        return flash_[a / 2];
    if (is_eeprom(a))
        return eeprom_[(a - eeprom_base) / 2];
    if (is_config(a))
        return config_[(a - config_base) / 2];
    if (a == device_id_address)
        return device_id;
    if (a == device_revision_address)
        return device_revision;
    return 0;
}

bool ProgramMemory::program(uint32_t address, uint32_t word)
{
    const uint32_t a = address & ~1u;
    if (is_flash(a))
        flash_[a / 2] = word & word_bits;
    else if (is_eeprom(a))
        eeprom_[(a - eeprom_base) / 2] = static_cast<uint16_t>(word);
    else if (is_config(a))
        config_[(a - config_base) / 2] = static_cast<uint16_t>(word);
    else
        return false;
    return true;
}

void ProgramMemory::erase_row(uint32_t address, uint32_t row_words, uint32_t done_words)
{
    const uint32_t span = 2 * row_words;
    const uint32_t first = address & ~(span - 1);
    const uint32_t end = first + 2 * std::min(row_words, done_words);
    for (uint32_t a = first; a < end; a += 2) {
        if (is_flash(a))
            flash_[a / 2] = erased_word;
        else if (is_eeprom(a))
            eeprom_[(a - eeprom_base) / 2] = erased_data_word;
    }
}

} // namespace aseba::dspic30
