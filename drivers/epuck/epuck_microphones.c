// Microphone volume: running minimum and maximum over a window.

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
}

void epuck_microphones_sampled(epuck_microphones *microphones, const uint16_t *values)
{
    uint8_t i;

    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++) {
        if (values[i] < microphones->window_min[i])
            microphones->window_min[i] = values[i];
        if (values[i] > microphones->window_max[i])
            microphones->window_max[i] = values[i];
    }
    microphones->window_samples++;
    if (microphones->window_samples < EPUCK_MICROPHONE_WINDOW)
        return;
    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++)
        microphones->volume[i] =
          (uint16_t)(microphones->window_max[i] - microphones->window_min[i]);
    start_window(microphones);
}

void epuck_microphones_read(epuck_microphones *microphones, int16_t *volume)
{
    hal_critical_state state = hal_critical_enter(microphones->board);
    uint8_t i;

    for (i = 0; i < EPUCK_MICROPHONE_COUNT; i++)
        volume[i] = (int16_t)microphones->volume[i];
    hal_critical_leave(microphones->board, state);
}
