// Setting the CPU up and looking at it: construction, loading program
// space, peripherals, and the register summary of traces and reports.

#include "tools/dspic30_sim/cpu_inline.hpp"

#include <cstdio>
#include <stdexcept>

namespace aseba::dspic30
{

Cpu::Cpu()
  : code_(flash_words)
{
    power_on_reset();
}

bool Cpu::program(uint32_t address, uint32_t word)
{
    if (!program_.program(address, word))
        return false;
    if (ProgramMemory::is_flash(address & ~1u))
        invalidate(address & ~1u, (address & ~1u) + 2);
    return true;
}

void Cpu::attach(uint16_t first, uint16_t last, Peripheral &peripheral)
{
    if (first < sfr::CORE_END || last >= sfr_end || first > last)
        throw std::invalid_argument("peripheral outside the SFR space");
    for (uint32_t a = first & ~1u; a <= last; a += 2)
        sfr_owner_[a / 2] = &peripheral;
    peripherals_.push_back(&peripheral);
    next_event_ = 0;
}

std::vector<uint32_t> Cpu::last_pcs() const
{
    std::vector<uint32_t> pcs;
    const uint64_t count = std::min<uint64_t>(instructions_, history_length);
    for (uint64_t i = instructions_ - count; i != instructions_; ++i)
        pcs.push_back(history_[i % history_length]);
    return pcs;
}

std::string Cpu::register_summary() const
{
    std::string text;
    char item[32];
    for (int n = 0; n < 16; ++n) {
        std::snprintf(item, sizeof item, "W%d=%04X ", n, w_[n]);
        text += item;
    }
    std::snprintf(
      item, sizeof item, "SR=%04X CORCON=%04X PC=%06X", sr_, corcon_, static_cast<unsigned>(pc_));
    text += item;
    return text;
}

} // namespace aseba::dspic30
