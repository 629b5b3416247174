// Accelerometer: the last sample, and offsets averaged at boot.

#include "epuck_accelerometer.h"

#define AXIS_Z 2u

void epuck_accelerometer_init(epuck_accelerometer *accelerometer, hal_board *board)
{
    uint8_t axis;

    accelerometer->board = board;
    accelerometer->calibration_samples = 0;
    for (axis = 0; axis < EPUCK_ACCELEROMETER_AXES; axis++) {
        accelerometer->calibration_sum[axis] = 0;
        accelerometer->offset[axis] = EPUCK_ACCELEROMETER_DEFAULT_XY_OFFSET;
        accelerometer->sample[axis] = EPUCK_ACCELEROMETER_DEFAULT_XY_OFFSET;
    }
    accelerometer->offset[AXIS_Z] = EPUCK_ACCELEROMETER_DEFAULT_Z_OFFSET;
}

void epuck_accelerometer_sampled(epuck_accelerometer *accelerometer, const uint16_t *values)
{
    uint8_t axis;

    for (axis = 0; axis < EPUCK_ACCELEROMETER_AXES; axis++)
        accelerometer->sample[axis] = values[axis];
    if (accelerometer->calibration_samples >= EPUCK_ACCELEROMETER_CALIBRATION_SAMPLES)
        return;
    for (axis = 0; axis < EPUCK_ACCELEROMETER_AXES; axis++)
        accelerometer->calibration_sum[axis] += values[axis];
    accelerometer->calibration_samples++;
    if (accelerometer->calibration_samples == EPUCK_ACCELEROMETER_CALIBRATION_SAMPLES) {
        for (axis = 0; axis < EPUCK_ACCELEROMETER_AXES; axis++)
            accelerometer->offset[axis] =
              (int16_t)(accelerometer->calibration_sum[axis] /
                        (int32_t)EPUCK_ACCELEROMETER_CALIBRATION_SAMPLES);
        // Upright and still, Z feels one g.
        accelerometer->offset[AXIS_Z] =
          (int16_t)(accelerometer->offset[AXIS_Z] - EPUCK_ACCELEROMETER_ONE_G);
    }
}

bool epuck_accelerometer_calibrated(epuck_accelerometer *accelerometer)
{
    hal_critical_state state = hal_critical_enter(accelerometer->board);
    bool calibrated = accelerometer->calibration_samples >= EPUCK_ACCELEROMETER_CALIBRATION_SAMPLES;

    hal_critical_leave(accelerometer->board, state);
    return calibrated;
}

void epuck_accelerometer_read(epuck_accelerometer *accelerometer, int16_t *acceleration)
{
    hal_critical_state state = hal_critical_enter(accelerometer->board);
    uint8_t axis;

    for (axis = 0; axis < EPUCK_ACCELEROMETER_AXES; axis++)
        acceleration[axis] =
          (int16_t)((int32_t)accelerometer->sample[axis] - accelerometer->offset[axis]);
    hal_critical_leave(accelerometer->board, state);
}
