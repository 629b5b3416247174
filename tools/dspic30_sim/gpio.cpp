// TRIS, PORT and LAT of the six ports: three consecutive words a port, six
// bytes apart, from TRISA at 0x02C0.

#include "tools/dspic30_sim/gpio.hpp"

namespace aseba::dspic30
{
namespace
{

constexpr uint16_t first_register = 0x02C0; // TRISA
constexpr uint16_t port_stride = 6;
constexpr uint16_t tris_offset = 0, port_offset = 2, latch_offset = 4;
// Implemented bits of ports A..G (fact sheet §2.5, from p30F6014A.inc); E
// does not exist on the 6014A.
constexpr std::array<uint16_t, GpioPorts::port_count> implemented_bits = {
    0xF6C0, // A: RA6, RA7, RA9, RA10, RA12-RA15
    0xFFFF, // B: RB0-RB15
    0xE01E, // C: RC1-RC4, RC13-RC15
    0xFFFF, // D: RD0-RD15
    0x0000, // E: none
    0x01FF, // F: RF0-RF8
    0xF3CF, // G: RG0-RG3, RG6-RG9, RG12-RG15
};
// The external interrupt INT0 is RF6 (fact sheet §1.7, §2.5); INTCON2.INT0EP
// chooses its edge: 1 falling, 0 rising.
constexpr char int0_port = 'F';
constexpr uint16_t int0_pin = 1u << 6;
constexpr int int0_irq = 0;
constexpr uint16_t int0_falling_edge = 1u << 0;

} // namespace

GpioPorts::GpioPorts(Cpu &cpu)
  : cpu_(cpu)
{
    for (int i = 0; i < port_count; ++i)
        ports_[i].implemented = implemented_bits[i];
    reset();
}

void GpioPorts::attach()
{
    cpu_.attach(
      first_register, static_cast<uint16_t>(first_register + port_stride * port_count - 2), *this);
}

int GpioPorts::index_of(char letter)
{
    return letter - 'A';
}

void GpioPorts::set_input_levels(char letter, uint16_t levels)
{
    Port &port = ports_.at(index_of(letter));
    const uint16_t before = pins(letter);
    port.outside = levels & port.implemented;
    if (letter == int0_port)
        watch_int0(before, pins(letter));
}

void GpioPorts::watch_int0(uint16_t before, uint16_t after)
{
    if (!((before ^ after) & int0_pin))
        return;
    const bool falling = (before & int0_pin) != 0;
    const bool on_falling = (cpu_.read_data(sfr::INTCON2) & int0_falling_edge) != 0;
    if (falling == on_falling)
        cpu_.raise_interrupt(int0_irq);
}

uint16_t GpioPorts::pins(char letter) const
{
    const Port &port = ports_.at(index_of(letter));
    return static_cast<uint16_t>(((port.latch & ~port.tris) | (port.outside & port.tris)) &
                                 port.implemented);
}

uint16_t GpioPorts::read(uint16_t address)
{
    const int index = (address - first_register) / port_stride;
    const Port &port = ports_[index];
    switch ((address - first_register) % port_stride) {
    case tris_offset: return port.tris;
    case port_offset:
        if (input_sampler_)
            input_sampler_(static_cast<char>('A' + index));
        return pins(static_cast<char>('A' + index));
    case latch_offset: return port.latch;
    default: return 0;
    }
}

void GpioPorts::write(uint16_t address, uint16_t value, uint16_t mask)
{
    const int index = (address - first_register) / port_stride;
    Port &port = ports_[index];
    const char letter = static_cast<char>('A' + index);
    const uint16_t before = pins(letter);
    const auto merged = [&](uint16_t old) {
        return static_cast<uint16_t>(((old & ~mask) | (value & mask)) & port.implemented);
    };
    if ((address - first_register) % port_stride == tris_offset)
        port.tris = merged(port.tris);
    else // PORTx and LATx both write the latch
        port.latch = merged(port.latch);
    const uint16_t after = pins(letter);
    if (letter == int0_port)
        watch_int0(before, after);
    if (pins_changed_ && after != before)
        pins_changed_(letter, before, after);
}

void GpioPorts::reset()
{
    for (Port &port : ports_) {
        port.tris = port.implemented; // every pin an input
        port.latch = 0;               // ⚠ undefined after a power-on reset
    }
}

} // namespace aseba::dspic30
