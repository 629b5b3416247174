// Microphone volume: running minimum and maximum over a window; recordings
// of consecutive readings.

#include "epuck_microphones.h"

static void start_window(epuck_microphones *microphones)
{
    uint8_t i;

    microphones->window_samples = 0;
    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++) {
        microphones->window_min[i] = EPUCK_ADC_MAX_VALUE;
        microphones->window_max[i] = 0;
    }
}

void epuck_microphones_init(epuck_microphones *microphones, hal_board *board)
{
    uint8_t i;

    microphones->board = board;
    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++)
        microphones->volume[i] = 0;
    start_window(microphones);
    microphones->recorded = 0;
    microphones->until_next = 0;
    microphones->recording_now = false;
    microphones->recording_full = false;
}

static void record(epuck_microphones *microphones, const uint16_t *values, bool follows_previous)
{
    uint8_t i;

    if (microphones->until_next > 0)
        microphones->until_next--;
    if (!microphones->recording_now) {
        // The main loop has not taken the last one yet, or it is too soon.
        if (microphones->recording_full || microphones->until_next > 0)
            return;
        microphones->recording_now = true;
        microphones->recorded = 0;
        microphones->until_next = EPUCK_MICROPHONE_RECORD_INTERVAL;
    } else if (!follows_previous) {
        // Another channel was converted meanwhile: the readings would not
        // be one scan apart.
        microphones->recorded = 0;
    }
    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++)
        microphones->recording[i][microphones->recorded] = values[i];
    microphones->recorded++;
    if (microphones->recorded == EPUCK_MICROPHONE_RECORD_SAMPLES) {
        microphones->recording_now = false;
        microphones->recording_full = true;
    }
}

static void widen_window(epuck_microphones *microphones, const uint16_t *values)
{
    uint8_t i;

    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++) {
        if (values[i] < microphones->window_min[i])
            microphones->window_min[i] = values[i];
        if (values[i] > microphones->window_max[i])
            microphones->window_max[i] = values[i];
    }
}

static void end_window(epuck_microphones *microphones)
{
    uint8_t i;

    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++)
        microphones->volume[i] =
          (uint16_t)(microphones->window_max[i] - microphones->window_min[i]);
    start_window(microphones);
}

void epuck_microphones_sampled(epuck_microphones *microphones,
                               const uint16_t *values,
                               bool follows_previous)
{
    record(microphones, values, follows_previous);
    widen_window(microphones, values);
    microphones->window_samples++;
    if (microphones->window_samples == EPUCK_MICROPHONE_WINDOW)
        end_window(microphones);
}

void epuck_microphones_sampled_run(epuck_microphones *microphones,
                                   const uint16_t *values,
                                   bool follows_previous,
                                   uint16_t scans)
{
    uint16_t left = scans;
    uint16_t take;

    while (left > 0) {
        if (!microphones->recording_now &&
            (microphones->recording_full || microphones->until_next > 1u)) {
            // Readings that only count down to the next recording: all of
            // them while one waits to be taken, else all but the one that
            // starts the next.
            take = microphones->recording_full ? left : (uint16_t)(microphones->until_next - 1u);
            if (take > left)
                take = left;
            microphones->until_next =
              microphones->until_next > take ? (uint16_t)(microphones->until_next - take) : 0u;
        } else {
            record(microphones, values, follows_previous);
            take = 1;
        }
        left = (uint16_t)(left - take);
        follows_previous = true;
    }
    // The same readings again leave the window's extremes as they are after
    // the first; only the count of readings moves.
    for (left = scans; left > 0; left = (uint16_t)(left - take)) {
        take = (uint16_t)(EPUCK_MICROPHONE_WINDOW - microphones->window_samples);
        if (take > left)
            take = left;
        widen_window(microphones, values);
        microphones->window_samples = (uint16_t)(microphones->window_samples + take);
        if (microphones->window_samples == EPUCK_MICROPHONE_WINDOW)
            end_window(microphones);
    }
}

void epuck_microphones_read(epuck_microphones *microphones, int16_t *volume)
{
    hal_critical_state state = hal_critical_enter(microphones->board);
    uint8_t i;

    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++)
        volume[i] = (int16_t)microphones->volume[i];
    hal_critical_leave(microphones->board, state);
}

bool epuck_microphones_take_recording(epuck_microphones *microphones,
                                      int16_t *const recordings[EPUCK_MICROPHONE_COUNT])
{
    hal_critical_state state;
    uint8_t i;
    uint16_t n;

    // Only the scan's interrupt sets the flag, only this clears it (as in
    // epuck_rc5_take): the critical section only once a recording waits.
    if (!microphones->recording_full)
        return false;
    state = hal_critical_enter(microphones->board);
    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++)
        for (n = 0; n < EPUCK_MICROPHONE_RECORD_SAMPLES; n++)
            recordings[i][n] = (int16_t)microphones->recording[i][n];
    microphones->recording_full = false;
    hal_critical_leave(microphones->board, state);
    // Readings are 12-bit, so 32 of them sum well within 32 bits.
    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++) {
        int32_t sum = 0;
        int16_t mean;

        for (n = 0; n < EPUCK_MICROPHONE_RECORD_SAMPLES; n++)
            sum += recordings[i][n];
        mean = (int16_t)((sum + (int32_t)(EPUCK_MICROPHONE_RECORD_SAMPLES / 2u)) /
                         (int32_t)EPUCK_MICROPHONE_RECORD_SAMPLES);
        for (n = 0; n < EPUCK_MICROPHONE_RECORD_SAMPLES; n++)
            recordings[i][n] = (int16_t)(recordings[i][n] - mean);
    }
    return true;
}
