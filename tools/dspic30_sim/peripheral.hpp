// What a simulated peripheral offers the CPU: its registers in the SFR space
// and its own sense of time, in instruction cycles.

#pragma once

#include <cstdint>
#include <limits>

namespace aseba::dspic30
{

inline constexpr uint64_t never = std::numeric_limits<uint64_t>::max();

class Peripheral
{
  public:
    virtual ~Peripheral() = default;

    // The register at even SFR address `address`, as the CPU reads it.
    virtual uint16_t read(uint16_t address) = 0;
    // Writes the bits of `mask` (0xFFFF, or one byte) of the register at
    // `address` with those of `value`.
    virtual void write(uint16_t address, uint16_t value, uint16_t mask) = 0;
    // The cycle at which advance() has something to do, or `never`.
    virtual uint64_t next_event() const
    {
        return never;
    }
    // Brings the peripheral up to cycle `now`.
    virtual void advance(uint64_t now)
    {
        (void)now;
    }
    // Back to the reset state (a device reset).
    virtual void reset() {}
};

} // namespace aseba::dspic30
