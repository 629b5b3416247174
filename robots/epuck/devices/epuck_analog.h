// The analog sequencer: one ADC scan running EPUCK_ADC_SCAN_RATE_HZ times a
// second, shared by the microphones, the accelerometer and the proximity
// sensors as the library's advanced scan shares it (hardware §3.2). A cycle
// is EPUCK_ANALOG_CYCLE scans; most scans convert the microphones, one the
// accelerometer, and two the current proximity pair: its ambient level, then
// (with its emitter on from then) its lit level EPUCK_ANALOG_PULSE_SCANS
// scans later. Each pair is thus measured about 252 times a second and the
// eight sensors about 63 times.

#ifndef EPUCK_ANALOG_H
#define EPUCK_ANALOG_H

#include <stdbool.h>
#include <stdint.h>

#include "epuck_accelerometer.h"
#include "epuck_microphones.h"
#include "epuck_proximity.h"
#include "robots/epuck/epuck_board.h"

// Scans per cycle: 16384 / 65 ≈ 252 pair measurements a second (§3.2).
#define EPUCK_ANALOG_CYCLE 65u
// Scans between the ambient sample (emitter switched on) and the lit sample
// (emitter switched off): 6 × 61 µs ≈ 366 µs (§3.2, counts 63 → 4).
#define EPUCK_ANALOG_PULSE_SCANS 6u

typedef enum epuck_analog_source {
    EPUCK_ANALOG_MICROPHONES,
    EPUCK_ANALOG_ACCELEROMETER,
    EPUCK_ANALOG_PROXIMITY_AMBIENT,
    EPUCK_ANALOG_PROXIMITY_LIT
} epuck_analog_source;

typedef struct epuck_analog {
    hal_board *board;
    epuck_proximity *proximity;
    epuck_accelerometer *accelerometer;
    epuck_microphones *microphones;
    uint8_t count;                // position in the cycle, 0..EPUCK_ANALOG_CYCLE-1
    epuck_analog_source scanning; // what the scan under way converts
    epuck_analog_source previous; // what the scan before it converted
} epuck_analog;

// Starts the ADC scan feeding the three drivers (already initialised);
// returns false when the board refuses the scan.
bool epuck_analog_start(epuck_analog *analog,
                        hal_board *board,
                        epuck_proximity *proximity,
                        epuck_accelerometer *accelerometer,
                        epuck_microphones *microphones);

// Stops the scan; the proximity emitters are left off.
void epuck_analog_stop(epuck_analog *analog);

#endif
