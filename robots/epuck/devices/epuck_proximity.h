// The eight infrared proximity sensors (hardware §3.2). The emitters are
// paired (sensors n and n+4 share one pulse line); for each pair the analog
// sequencer (epuck_analog.h) samples the ambient level, switches the pair's
// emitter on, samples again about 300 µs later and switches it off. More
// light reads lower, so reflected = ambient − lit. The first
// EPUCK_PROXIMITY_CALIBRATION_SETS full sets (the robot is kept still at
// boot, §6.6) give each sensor's offset; a value is reflected − offset,
// floored at 0. Sets measured during the calibration are reported too, with
// the offsets still 0, so that `ir_sensors` keeps its rate from boot.

#ifndef EPUCK_PROXIMITY_H
#define EPUCK_PROXIMITY_H

#include <stdbool.h>
#include <stdint.h>

#include "robots/epuck/epuck_board.h"

#define EPUCK_PROXIMITY_COUNT 8u
#define EPUCK_PROXIMITY_PAIRS 4u
// Readings averaged per sensor for the offset (§3.2: 100).
#define EPUCK_PROXIMITY_CALIBRATION_SETS 100u

typedef struct epuck_proximity {
    hal_board *board;
    uint8_t pair;                                    // the pair being measured, 0..3
    uint16_t ambient_reading[EPUCK_PROXIMITY_COUNT]; // raw ADC, emitter off
    int16_t reflected[EPUCK_PROXIMITY_COUNT];        // ambient − lit, last set
    int32_t calibration_sum[EPUCK_PROXIMITY_COUNT];
    int16_t offset[EPUCK_PROXIMITY_COUNT];
    uint16_t calibration_sets; // full sets summed so far
    bool offsets_set;          // from the sums, once calibration_sets is complete
    bool fresh;                // a full set completed, not yet taken
} epuck_proximity;

// Prepares the sensors on `board`, emitters off, uncalibrated.
void epuck_proximity_init(epuck_proximity *proximity, hal_board *board);

// The ADC channels of the pair being measured (bit n = ANn).
uint16_t epuck_proximity_channels(const epuck_proximity *proximity);

// Takes the pair's ambient readings (lower channel first) and switches its
// emitter on. Called by the sequencer in interrupt context.
void epuck_proximity_ambient_sampled(epuck_proximity *proximity, const uint16_t *values);

// Takes the pair's lit readings (lower channel first), switches its emitter
// off and moves to the next pair; after the last pair a full set is
// complete. Called by the sequencer in interrupt context.
void epuck_proximity_lit_sampled(epuck_proximity *proximity, const uint16_t *values);

// Whether the boot calibration is over.
bool epuck_proximity_calibrated(epuck_proximity *proximity);

// When a full set completed since the last call, copies the
// calibrated values (≥ 0) into `prox` and the raw ambient readings into
// `ambient` and returns true; otherwise returns false, copying nothing.
bool epuck_proximity_take(epuck_proximity *proximity, int16_t *prox, int16_t *ambient);

#endif
