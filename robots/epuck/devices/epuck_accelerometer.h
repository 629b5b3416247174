// The three-axis analog accelerometer (hardware §3.3, MMA7260 on boards
// before revision 1.3): X, Y, Z on AN5..AN7, about 2048 counts at 0 g and
// 768 counts per g. The first EPUCK_ACCELEROMETER_CALIBRATION_SAMPLES
// samples (the robot is kept still and upright at boot, §6.6) give the
// offsets: X and Y their average, Z its average less one g, so that a still
// upright robot reads (0, 0, 768).

#ifndef EPUCK_ACCELEROMETER_H
#define EPUCK_ACCELEROMETER_H

#include <stdbool.h>
#include <stdint.h>

#include "robots/epuck/epuck_board.h"

#define EPUCK_ACCELEROMETER_AXES 3u
// Samples averaged for the offsets (§3.3: 50).
#define EPUCK_ACCELEROMETER_CALIBRATION_SAMPLES 50u
// Counts per g (§3.3: the library's GRAVITY).
#define EPUCK_ACCELEROMETER_ONE_G 768
// Offsets before calibration (§3.3): zero g for X and Y, and the library's
// default Z centre.
#define EPUCK_ACCELEROMETER_DEFAULT_XY_OFFSET 2048
#define EPUCK_ACCELEROMETER_DEFAULT_Z_OFFSET  2000

typedef struct epuck_accelerometer {
    hal_board *board;
    uint16_t sample[EPUCK_ACCELEROMETER_AXES]; // last raw reading
    int32_t calibration_sum[EPUCK_ACCELEROMETER_AXES];
    int16_t offset[EPUCK_ACCELEROMETER_AXES];
    uint16_t calibration_samples; // summed so far
} epuck_accelerometer;

// The ADC channels of the three axes (bit n = ANn).
#define EPUCK_ACCELEROMETER_CHANNELS                                                               \
    ((uint16_t)((1u << EPUCK_ADC_ACCELEROMETER_X) | (1u << EPUCK_ADC_ACCELEROMETER_Y) |            \
                (1u << EPUCK_ADC_ACCELEROMETER_Z)))

// Prepares the accelerometer, uncalibrated.
void epuck_accelerometer_init(epuck_accelerometer *accelerometer, hal_board *board);

// Takes one reading of X, Y, Z (interrupt context, from the sequencer).
void epuck_accelerometer_sampled(epuck_accelerometer *accelerometer, const uint16_t *values);

// Whether the boot calibration is over.
bool epuck_accelerometer_calibrated(epuck_accelerometer *accelerometer);

// The last reading less the offsets, X, Y, Z, into `acceleration`.
void epuck_accelerometer_read(epuck_accelerometer *accelerometer, int16_t *acceleration);

#endif
