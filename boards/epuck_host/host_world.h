// What a simulated e-puck's pins see: the world around the robot, behind a
// table of functions so that a simulator (Enki) can plug in its own. The
// flat world stands for a still robot on an empty, evenly lit floor.
//
// Times are processor cycles since the board started (HOST_CYCLES_PER_SECOND
// of them a second, epuck_host_config.h), so that the world sees exactly when the
// firmware samples.

#ifndef HOST_WORLD_H
#define HOST_WORLD_H

#include <stdbool.h>
#include <stdint.h>

#include "robots/epuck/epuck_board.h"

typedef struct host_world {
    // Passed back to every function.
    void *context;
    // The value 0..4095 analog input `channel` converts to at time `cycle`.
    uint16_t (*adc_read)(void *context, uint8_t channel, uint64_t cycle);
    // The level of input pin `pin` at time `cycle`.
    bool (*pin_read)(void *context, epuck_pin pin, uint64_t cycle);
    // Output pin `pin` now drives `high` (LEDs, motor phases, IR pulses...).
    void (*pin_written)(void *context, epuck_pin pin, bool high, uint64_t cycle);
    // An I2C write/read of `count` bytes at register `reg` of the device at
    // 8-bit address `device`; false when no device acknowledges.
    bool (
      *i2c_write)(void *context, uint8_t device, uint8_t reg, const uint8_t *bytes, uint16_t count);
    bool (*i2c_read)(void *context, uint8_t device, uint8_t reg, uint8_t *bytes, uint16_t count);
    // Byte `index` the camera sends on row `row` of its window.
    uint8_t (*camera_byte)(void *context, uint16_t row, uint16_t index, uint64_t cycle);
    // The first cycle after `after_cycle` at which an input pin may change
    // level (HOST_NO_INPUT_CHANGE: none foreseen), so that the board signals
    // an edge at the cycle it happens, as the chip's edge interrupt would
    // (the remote's INT0). NULL for a world whose inputs keep their levels.
    // The board asks again after every event other than an ADC scan, and
    // once the time it was told has come: the answer must hold meanwhile.
    uint64_t (*next_input_change)(void *context, uint64_t after_cycle);
    // The values of the analog inputs of `channel_mask` (bit n = ANn) at
    // `cycle`, lowest channel first, into `values`: what adc_read gives for
    // each, in one call for a whole ADC scan (16,384 a second). NULL: the
    // board calls adc_read for each channel.
    void (*adc_read_channels)(void *context,
                              uint16_t channel_mask,
                              uint64_t cycle,
                              uint16_t *values);
    // Whether the analog inputs of `channel_mask` convert to the same values
    // at every cycle until the board's current advance ends, whatever the
    // firmware writes to the pins meanwhile (a silent arena's microphones),
    // so that the board hands a run of scans to the firmware at once
    // (epuck_board_adc_scan_runs). NULL: never.
    bool (*adc_channels_steady)(void *context, uint16_t channel_mask);
    // The bytes of every second pixel of row `row` from the first, `pixels`
    // of them, into `bytes`: what camera_byte gives for each, in one call
    // for a whole row, so that the world works out only the pixels read.
    // NULL: the board calls camera_byte for each byte.
    void (*camera_every_second_pixel)(void *context,
                                      uint16_t row,
                                      uint16_t pixels,
                                      uint64_t cycle,
                                      uint8_t *bytes);
    // The levels of the `count` input pins from `first` on at `cycle`, pin
    // first + i in bit i: what pin_read gives for each, in one call (the
    // selector's bits, read every millisecond). NULL: the board calls
    // pin_read for each.
    uint16_t (*inputs_read)(void *context, epuck_pin first, uint8_t count, uint64_t cycle);
    // Whether next_input_change's answers hold until the cycle they give
    // whatever the firmware does meanwhile (the arena's remote, whose
    // frames are sent between the board's advances): the board then asks
    // again once that cycle has come or a peripheral started or stopped,
    // not after every other event (a motor's step, a thousand a second).
    bool input_changes_fixed;
} host_world;

#define HOST_NO_INPUT_CHANGE UINT64_MAX

// Neutral values of the flat world.
#define HOST_FLAT_MICROPHONE      2048u          // silence: the middle of the range
#define HOST_FLAT_ACCELERATION_XY 2048u          // zero g (§3.3)
#define HOST_FLAT_ACCELERATION_Z  (2048u + 768u) // one g: upright and still (§3.3)
#define HOST_FLAT_PROXIMITY       3800u          // an unlit phototransistor, no reflection
#define HOST_FLAT_OTHER_INPUT     0u

// The flat world: the values above whatever the outputs do, selector at 0,
// battery fine, remote silent (high), no I2C device, a black camera.
const host_world *host_world_flat(void);

#endif
