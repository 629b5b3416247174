// Timers 1-5 of the dsPIC30F6014A (fact sheet §2.2): TMRx counts the
// instruction clock through its prescaler (1, 8, 64, 256) while TxCON.TON is
// set; on reaching PRx it restarts from 0 and sets its interrupt flag (a
// period of PRx + 1 counts). Timers 2 and 3, and 4 and 5, pair into 32-bit
// timers with T2CON.T32 (T4CON.T32); TMR3HLD (TMR5HLD) holds the high word
// latched when the low word is read, and gives it to the high word when the
// low word is written. An external clock (TCS = 1) and gated counting
// (TGATE) are not modelled: such a timer does not count.

#pragma once

#include "tools/dspic30_sim/cpu.hpp"
#include "tools/dspic30_sim/peripheral.hpp"

#include <array>
#include <cstdint>

namespace aseba::dspic30
{

class Timers : public Peripheral
{
  public:
    explicit Timers(Cpu &cpu);

    // Attaches the timers' registers (0x0100-0x0120) to the CPU.
    void attach();

    uint16_t read(uint16_t address) override;
    void write(uint16_t address, uint16_t value, uint16_t mask) override;
    uint64_t next_event() const override;
    void advance(uint64_t now) override;
    void reset() override;

  private:
    // One 16-bit timer, or the 32-bit pair whose low half it is.
    struct Counter {
        uint32_t count = 0;
        uint64_t synced_at = 0; // the cycle `count` is for
        uint64_t phase = 0;     // cycles into the current prescaler count
        uint64_t match_at = never;
    };

    bool paired(int timer) const;
    bool counting(int timer) const;
    uint64_t prescale(int timer) const;
    uint32_t period(int timer) const;
    void sync(int timer, uint64_t now);
    void schedule(int timer, uint64_t now);

    Cpu &cpu_;
    std::array<Counter, 6> counters_{}; // by timer number 1..5
    std::array<uint16_t, 6> control_{};
    std::array<uint16_t, 6> period_{};
    std::array<uint16_t, 6> high_latch_{}; // TMR3HLD (index 3), TMR5HLD (5)
};

} // namespace aseba::dspic30
