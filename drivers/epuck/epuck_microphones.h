// The three microphones (hardware §3.4) on AN2..AN4. The volume of a
// microphone is the difference between its highest and lowest readings over
// a window of EPUCK_MICROPHONE_WINDOW samples, as the library computes it
// over its 100-sample buffer.

#ifndef EPUCK_MICROPHONES_H
#define EPUCK_MICROPHONES_H

#include <stdint.h>

#include "epuck_board.h"

#define EPUCK_MICROPHONE_COUNT  3u
#define EPUCK_MICROPHONE_WINDOW 100u

// The ADC channels of the three microphones (bit n = ANn).
#define EPUCK_MICROPHONE_CHANNELS                                                                  \
    ((uint16_t)(((1u << EPUCK_MICROPHONE_COUNT) - 1u) << EPUCK_ADC_MICROPHONE_0))

typedef struct epuck_microphones {
    hal_board *board;
    uint16_t window_min[EPUCK_MICROPHONE_COUNT];
    uint16_t window_max[EPUCK_MICROPHONE_COUNT];
    uint16_t window_samples;                 // taken in the current window
    uint16_t volume[EPUCK_MICROPHONE_COUNT]; // of the last full window
} epuck_microphones;

// Prepares the microphones, volumes 0.
void epuck_microphones_init(epuck_microphones *microphones, hal_board *board);

// Takes one reading of each microphone (interrupt context, from the
// sequencer); a full window updates the volumes.
void epuck_microphones_sampled(epuck_microphones *microphones, const uint16_t *values);

// The volumes of the last full window (max − min, 0..4095) into `volume`.
void epuck_microphones_read(epuck_microphones *microphones, int16_t *volume);

#endif
