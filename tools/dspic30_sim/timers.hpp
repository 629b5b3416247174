// Timers 1-5 of the dsPIC30F6014A (fact sheet §2.2): TMRx counts the
// instruction clock through its prescaler (1, 8, 64, 256) while TxCON.TON is
// set; on reaching PRx it restarts from 0 and sets its interrupt flag (a
// period of PRx + 1 counts). Timers 2 and 3, and 4 and 5, pair into 32-bit
// timers with T2CON.T32 (T4CON.T32); TMR3HLD (TMR5HLD) holds the high word
// latched when the low word is read, and gives it to the high word when the
// low word is written. With TCS = 1 a timer counts the rising edges of
// its TxCK pin instead, through the same prescaler, when the simulator's
// host has given that pin a signal (connect_clock; else it does not count);
// an edge is counted at its own cycle (the pin's synchroniser delay, a
// cycle or two, is not modelled). Gated counting (TGATE) is not modelled.

#pragma once

#include "tools/dspic30_sim/cpu.hpp"
#include "tools/dspic30_sim/peripheral.hpp"

#include <array>
#include <cstdint>

namespace aseba::dspic30
{

// A signal on a timer's external clock pin (TxCK), known as its rising
// edges on the chip's clock: what a timer with TCS = 1 counts.
class ClockInput
{
  public:
    virtual ~ClockInput() = default;
    // The number of rising edges at cycles after `from`, up to `to`.
    virtual uint64_t rising_edges(uint64_t from, uint64_t to) const = 0;
    // The cycle of the `n`-th (n >= 1) rising edge after cycle `after`, or
    // `never`.
    virtual uint64_t rising_edge(uint64_t after, uint64_t n) const = 0;
};

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

    // Timer `timer` (1-5) counts `input`'s rising edges when TCS = 1 (its
    // TxCK pin); nullptr: no signal, the timer then does not count.
    // `input` outlives the timers.
    void connect_clock(int timer, const ClockInput *input);

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
    const ClockInput *external_clock(int timer) const;
    uint64_t prescale(int timer) const;
    uint32_t period(int timer) const;
    void sync(int timer, uint64_t now);
    void schedule(int timer, uint64_t now);

    Cpu &cpu_;
    std::array<Counter, 6> counters_{}; // by timer number 1..5
    std::array<uint16_t, 6> control_{};
    std::array<uint16_t, 6> period_{};
    std::array<uint16_t, 6> high_latch_{}; // TMR3HLD (index 3), TMR5HLD (5)
    std::array<const ClockInput *, 6> clock_inputs_{};
};

} // namespace aseba::dspic30
