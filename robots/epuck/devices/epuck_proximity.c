// Proximity: per pair an ambient and a lit reading, then calibration and the
// floor at zero when a full set is complete.

#include "epuck_proximity.h"

static epuck_pin pulse_pin(uint8_t pair)
{
    return (epuck_pin)(EPUCK_PIN_IR_PULSE_0_4 + pair);
}

void epuck_proximity_init(epuck_proximity *proximity, hal_board *board)
{
    uint8_t i;

    proximity->board = board;
    proximity->pair = 0;
    proximity->calibration_sets = 0;
    proximity->offsets_set = false;
    proximity->fresh = false;
    for (i = 0; i < EPUCK_PROXIMITY_COUNT; i++) {
        proximity->ambient_reading[i] = 0;
        proximity->reflected[i] = 0;
        proximity->calibration_sum[i] = 0;
        proximity->offset[i] = 0;
    }
    for (i = 0; i < EPUCK_PROXIMITY_PAIRS; i++)
        epuck_board_pin_write(board, pulse_pin(i), false);
}

uint16_t epuck_proximity_channels(const epuck_proximity *proximity)
{
    uint8_t first = (uint8_t)(EPUCK_ADC_PROXIMITY_0 + proximity->pair);
    return (uint16_t)((1u << first) | (1u << (first + EPUCK_PROXIMITY_PAIRS)));
}

void epuck_proximity_ambient_sampled(epuck_proximity *proximity, const uint16_t *values)
{
    proximity->ambient_reading[proximity->pair] = values[0];
    proximity->ambient_reading[proximity->pair + EPUCK_PROXIMITY_PAIRS] = values[1];
    epuck_board_pin_write(proximity->board, pulse_pin(proximity->pair), true);
}

// A full set is complete: it is ready, and goes into the calibration while
// that lasts. (Called from the scan's interrupt: the sums are divided into
// offsets later, in epuck_proximity_take, as 32-bit divisions take too long
// there on a 16-bit chip.)
static void set_complete(epuck_proximity *proximity)
{
    uint8_t i;

    if (proximity->calibration_sets < EPUCK_PROXIMITY_CALIBRATION_SETS) {
        for (i = 0; i < EPUCK_PROXIMITY_COUNT; i++)
            proximity->calibration_sum[i] += proximity->reflected[i];
        proximity->calibration_sets++;
    }
    proximity->fresh = true;
}

void epuck_proximity_lit_sampled(epuck_proximity *proximity, const uint16_t *values)
{
    uint8_t pair = proximity->pair;

    epuck_board_pin_write(proximity->board, pulse_pin(pair), false);
    proximity->reflected[pair] = (int16_t)((int32_t)proximity->ambient_reading[pair] - values[0]);
    proximity->reflected[pair + EPUCK_PROXIMITY_PAIRS] =
      (int16_t)((int32_t)proximity->ambient_reading[pair + EPUCK_PROXIMITY_PAIRS] - values[1]);
    proximity->pair = (uint8_t)((pair + 1u) % EPUCK_PROXIMITY_PAIRS);
    if (proximity->pair == 0)
        set_complete(proximity);
}

bool epuck_proximity_calibrated(epuck_proximity *proximity)
{
    hal_critical_state state = hal_critical_enter(proximity->board);
    bool calibrated = proximity->calibration_sets >= EPUCK_PROXIMITY_CALIBRATION_SETS;

    hal_critical_leave(proximity->board, state);
    return calibrated;
}

bool epuck_proximity_take(epuck_proximity *proximity, int16_t *prox, int16_t *ambient)
{
    hal_critical_state state;
    uint8_t i;

    // The sums no longer change once the calibration is over.
    if (!proximity->offsets_set && epuck_proximity_calibrated(proximity)) {
        for (i = 0; i < EPUCK_PROXIMITY_COUNT; i++)
            proximity->offset[i] =
              (int16_t)(proximity->calibration_sum[i] / (int32_t)EPUCK_PROXIMITY_CALIBRATION_SETS);
        proximity->offsets_set = true;
    }
    // Only the scan's interrupt sets the flag, only this clears it (as in
    // epuck_rc5_take): the critical section only once a set waits.
    if (!proximity->fresh)
        return false;
    state = hal_critical_enter(proximity->board);
    for (i = 0; i < EPUCK_PROXIMITY_COUNT; i++) {
        int32_t value = (int32_t)proximity->reflected[i] - proximity->offset[i];
        prox[i] = (int16_t)(value < 0 ? 0 : value);
        ambient[i] = (int16_t)proximity->ambient_reading[i];
    }
    proximity->fresh = false;
    hal_critical_leave(proximity->board, state);
    return true;
}
