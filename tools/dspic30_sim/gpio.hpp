// The dsPIC30F6014A's I/O ports A, B, C, D, F and G (no port E), each a
// TRISx, PORTx, LATx triple (hardware fact sheet §2.5, the addresses and
// implemented bits from Microchip's p30F6014A.inc). As the family reference
// manual's I/O Ports section gives them: TRISx reads what was written and
// is all ones (inputs) after a reset; a write to PORTx writes LATx; LATx
// reads the latch; PORTx reads the pins: the latch where TRIS makes the pin
// an output, the outside world's level where it is an input. Bits a port
// does not implement read 0 in all three, and so do port E's addresses.
// The outside world's levels are set by the simulator's host
// (set_input_levels: 0 for every pin until then; the e-puck's selector on
// RG6-RG9 then reads position 0), or asked of it at each read of a PORTx
// (set_input_sampler), and the host may watch the pins the program drives
// (set_pins_changed). An edge of RF6, the level the host sets or the latch
// the program writes, raises INT0 when it is the edge INTCON2.INT0EP
// chooses; the other external interrupts (INT1-INT4) are not modelled.

#pragma once

#include "tools/dspic30_sim/cpu.hpp"
#include "tools/dspic30_sim/peripheral.hpp"

#include <array>
#include <cstdint>
#include <functional>

namespace aseba::dspic30
{

class GpioPorts : public Peripheral
{
  public:
    // The ports by letter, in address order (E is absent on the 6014A).
    static constexpr int port_count = 7; // A..G, E included as a hole

    explicit GpioPorts(Cpu &cpu);

    // Attaches TRISA..LATG to `cpu`.
    void attach();

    // The outside world drives the input pins of port `letter` ('A'..'G')
    // to `levels` (bits of output pins are not read).
    void set_input_levels(char letter, uint16_t levels);
    // What the pins of port `letter` show: the latch on outputs, the
    // outside levels on inputs.
    uint16_t pins(char letter) const;
    // Calls `sampler(letter)` before each read of PORTx, so that the host
    // sets the levels of that instant (set_input_levels); empty: none.
    void set_input_sampler(std::function<void(char letter)> sampler)
    {
        input_sampler_ = std::move(sampler);
    }
    // Calls `changed(letter, before, after)` after each write of TRISx,
    // PORTx or LATx that changed what the port's pins show.
    void set_pins_changed(std::function<void(char letter, uint16_t before, uint16_t after)> changed)
    {
        pins_changed_ = std::move(changed);
    }

    uint16_t read(uint16_t address) override;
    void write(uint16_t address, uint16_t value, uint16_t mask) override;
    void reset() override;

  private:
    struct Port {
        uint16_t implemented = 0;
        uint16_t tris = 0, latch = 0, outside = 0;
    };
    static int index_of(char letter);
    // Raises INT0 if RF6 went from `before` to `after` on its chosen edge.
    void watch_int0(uint16_t before, uint16_t after);

    Cpu &cpu_;
    std::array<Port, port_count> ports_{};
    std::function<void(char)> input_sampler_;
    std::function<void(char, uint16_t, uint16_t)> pins_changed_;
};

} // namespace aseba::dspic30
