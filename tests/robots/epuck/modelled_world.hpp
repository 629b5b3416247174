// A world for the driver tests: what the e-puck's peripherals would show,
// set by each test, and a record of everything the board drives. It models
// the proximity sensors (a phototransistor reads lower while its pair's
// emitter is on and an obstacle reflects), the accelerometer and
// microphones (values per channel, or a function of time), the input pins,
// and a PO3030K camera as a register file on I2C with an RGB565 pixel port.

#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

extern "C" {
#include "robots/epuck/devices/epuck_microphones.h"
#include "boards/epuck_host/host_board.h"
}

namespace drivers_test
{

constexpr double FCY = 7372800.0 * 8 / 4; // hardware §1.6

// One output pin change, as the world saw it.
struct PinChange {
    epuck_pin pin;
    bool high;
    uint64_t cycle;
};

// One ADC conversion the world answered.
struct Conversion {
    uint8_t channel;
    uint64_t cycle;
};

struct ModelledWorld {
    // Proximity: the ambient reading of each sensor, and how much lower it
    // reads while its pair's emitter is on.
    std::array<uint16_t, 8> ambient{};
    std::array<uint16_t, 8> reflection{};
    // Other channels (microphones, accelerometer), unless `signal` is set.
    std::array<uint16_t, EPUCK_ADC_CHANNEL_COUNT> channel{};
    std::function<uint16_t(uint8_t channel, uint64_t cycle)> signal;
    // Whether the world tells the board that the microphones hold still
    // without `signal` (host_world.h: the board then hands runs of scans to
    // the firmware at once); their conversions are then recorded once a run.
    bool steady_microphones = false;
    // Input pins, unless `input_signal` is set; when set,
    // `next_input_change` says when they may change next (host_world.h).
    std::array<bool, EPUCK_PIN_COUNT> input{};
    std::function<bool(epuck_pin pin, uint64_t cycle)> input_signal;
    std::function<uint64_t(uint64_t after_cycle)> next_input_change;

    // A PO3030K: its registers, the identification in 0x00/0x01, and the
    // bytes of each row it sends.
    bool camera_present = false;
    std::array<uint8_t, 256> camera_registers{};
    std::vector<std::pair<uint8_t, uint8_t>> camera_writes; // in order
    std::function<uint8_t(uint16_t row, uint16_t index)> camera_pixels;
    std::vector<uint16_t> camera_rows_read;

    std::vector<PinChange> changes;
    std::vector<Conversion> conversions;
    std::array<bool, EPUCK_PIN_COUNT> output{};

    host_world table;

    ModelledWorld();
    // Attaches this world to `board` (which must not outlive it).
    void attach(hal_board *board);
    // The changes of `pin` recorded so far.
    std::vector<PinChange> changes_of(epuck_pin pin) const;
};

} // namespace drivers_test
