// An e-puck of the arena on its simulated dsPIC30F6014A: the chip
// (tools/dspic30_sim) runs a real image (the factory image: bootloader and
// application), and the e-puck's board around it is fed from the robot's
// host_world (enki_world.hpp), the same table a host board reads:
//
// - the analog inputs: each conversion holds what the world's adc_read
//   gives for that channel at that cycle (proximity with or without the IR
//   pulse the firmware drives, accelerometer, microphones);
// - the output pins the firmware drives (LEDs, stepper phases, IR pulses,
//   the camera's reset) go to the world's pin_written at the cycle they
//   change: the world turns the phases into wheel speeds;
// - the input pins (selector, BATT_LOW, the remote's line) are the world's
//   pin_read at each read of their port;
// - the I2C bus holds the camera at its address, its registers the world's;
// - the camera's pixel port runs on the chip's clock (dspic30_pixel_port.hpp).
//
// The pins are those of boards/epuck_dspic30/dspic30_pin_map.h. Not modelled:
// the remote's INT0 edge interrupt (the simulator has no external
// interrupts), so RC5 frames do not reach the firmware.

#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <vector>

#include "tools/dspic30_sim/simulator.hpp"
#include "tools/emulator/dspic30_pixel_port.hpp"

extern "C" {
#include "boards/epuck_host/host_world.h"
}

namespace aseba::arena
{

class Dspic30Robot
{
  public:
    // A chip with `image` (PC address -> word) programmed, from reset at
    // cycle 0, on a board that sees `world`, which must outlive the robot.
    // Throws std::invalid_argument as Simulator::load does.
    Dspic30Robot(const std::map<uint32_t, uint32_t> &image, const host_world &world);
    ~Dspic30Robot();
    Dspic30Robot(const Dspic30Robot &) = delete;
    Dspic30Robot &operator=(const Dspic30Robot &) = delete;

    // Runs the chip until its clock reaches `cycle` (the world's time:
    // HOST_CYCLES_PER_SECOND is the chip's instruction rate); says how the
    // run ended (Outcome::cycle_limit unless the chip failed).
    dspic30::Outcome run_until(uint64_t cycle);

    // Bytes for UART1's receiver, taken at the baud rate the firmware set.
    void receive(const uint8_t *bytes, size_t count);
    // The bytes UART1 transmitted since the last call.
    std::vector<uint8_t> take_output();

    // The level output `pin` drives now.
    bool output(epuck_pin pin) const;

    dspic30::Simulator &chip()
    {
        return *chip_;
    }

  private:
    class CameraBus;

    void sample_inputs(char letter);
    void pins_changed(char letter, uint16_t before, uint16_t after);

    const host_world &world_;
    Dspic30PixelPort pixel_port_;
    std::unique_ptr<CameraBus> camera_bus_;
    std::deque<uint8_t> to_chip_;
    std::vector<uint8_t> from_chip_;
    std::unique_ptr<dspic30::Simulator> chip_;
};

} // namespace aseba::arena
