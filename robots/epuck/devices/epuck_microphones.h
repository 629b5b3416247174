// The three microphones (hardware §3.4) on AN2..AN4. The volume of a
// microphone is the difference between its highest and lowest readings over
// a window of EPUCK_MICROPHONE_WINDOW samples, as the library computes it
// over its 100-sample buffer.
//
// Recordings, for sound localisation with the dsp.* natives: about 15 times
// a second, EPUCK_MICROPHONE_RECORD_SAMPLES readings of each microphone in a
// row, one per ADC scan (16384 a second, EPUCK_ADC_SCAN_RATE_HZ), with no
// other channel converted between them, so that a delay between two
// microphones is a whole number of scans. The main loop takes a recording
// with each microphone's mean removed (the microphones' bias, about 2048).
//
// Which microphone is where is not in the sources the fact sheet read
// (⚠ §3.4); GCtronic's e-puck2 keeps the e-puck's numbering for its first
// three (0 right, 1 left, 2 back), and the simulated arena places them so
// (docs/arena-format.md).

#ifndef EPUCK_MICROPHONES_H
#define EPUCK_MICROPHONES_H

#include <stdbool.h>
#include <stdint.h>

#include "robots/epuck/epuck_board.h"

#define EPUCK_MICROPHONE_COUNT  3u
#define EPUCK_MICROPHONE_WINDOW 100u
// Readings of each microphone in a recording, and readings from the start
// of one recording to the start of the next: 1024 of the about 15600
// microphone readings a second (62 scans in 65, epuck_analog.h).
#define EPUCK_MICROPHONE_RECORD_SAMPLES  32u
#define EPUCK_MICROPHONE_RECORD_INTERVAL 1024u

// The ADC channels of the three microphones (bit n = ANn).
#define EPUCK_MICROPHONE_CHANNELS                                                                  \
    ((uint16_t)(((1u << EPUCK_MICROPHONE_COUNT) - 1u) << EPUCK_ADC_MICROPHONE_0))

typedef struct epuck_microphones {
    hal_board *board;
    uint16_t window_min[EPUCK_MICROPHONE_COUNT];
    uint16_t window_max[EPUCK_MICROPHONE_COUNT];
    uint16_t window_samples;                 // taken in the current window
    uint16_t volume[EPUCK_MICROPHONE_COUNT]; // of the last full window
    // The recording under way or waiting to be taken.
    uint16_t recording[EPUCK_MICROPHONE_COUNT][EPUCK_MICROPHONE_RECORD_SAMPLES];
    uint16_t recorded;   // readings in the recording so far
    uint16_t until_next; // readings before the next recording may start
    bool recording_now;  // a recording is under way
    bool recording_full; // a whole recording waits for the main loop
} epuck_microphones;

// Prepares the microphones, volumes 0; the first recording starts with the
// first reading.
void epuck_microphones_init(epuck_microphones *microphones, hal_board *board);

// Takes one reading of each microphone (interrupt context, from the
// sequencer); `follows_previous` says that the scan before this one read the
// microphones too. A full window updates the volumes; a reading after a gap
// starts the recording under way again.
void epuck_microphones_sampled(epuck_microphones *microphones,
                               const uint16_t *values,
                               bool follows_previous);

// The same as `scans` calls of epuck_microphones_sampled with the same
// `values`, the first with `follows_previous`, the others following it: a
// simulated board hands a silent stretch at once (epuck_board.h, scan runs).
void epuck_microphones_sampled_run(epuck_microphones *microphones,
                                   const uint16_t *values,
                                   bool follows_previous,
                                   uint16_t scans);

// The volumes of the last full window (max − min, 0..4095) into `volume`.
void epuck_microphones_read(epuck_microphones *microphones, int16_t *volume);

// When a recording is complete and not yet taken, writes microphone i's
// readings, less their mean (rounded), into recordings[i]
// (EPUCK_MICROPHONE_RECORD_SAMPLES words each) and returns true; otherwise
// false.
bool epuck_microphones_take_recording(epuck_microphones *microphones,
                                      int16_t *const recordings[EPUCK_MICROPHONE_COUNT]);

#endif
