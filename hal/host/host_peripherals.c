// The host board's peripherals that face the world: ADC, pins, I2C and the
// camera's pixel port, each answered by the board's world at the board's
// current time.

#include "host_board.h"

#define SCAN_PERIOD_CYCLES (HOST_CYCLES_PER_SECOND / HAL_ADC_SCAN_RATE_HZ)

uint16_t hal_adc_read(hal_board *board, uint8_t channel)
{
    if (channel >= HAL_ADC_CHANNEL_COUNT || board->adc_scan_mask != 0)
        return 0;
    return board->world->adc_read(board->world->context, channel, board->cycles);
}

static bool scan_mask_supported(uint16_t mask)
{
    uint8_t count = 0;
    for (; mask != 0; mask = (uint16_t)(mask >> 1))
        count = (uint8_t)(count + (mask & 1u));
    return count >= HAL_ADC_SCAN_MIN_CHANNELS && count <= HAL_ADC_SCAN_MAX_CHANNELS;
}

bool hal_adc_scan_start(hal_board *board,
                        uint16_t channel_mask,
                        hal_adc_scan_callback callback,
                        void *context)
{
    if (!scan_mask_supported(channel_mask))
        return false;
    board->adc_scan_callback = callback;
    board->adc_scan_context = context;
    board->adc_scan_mask = channel_mask;
    board->adc_next_due = board->cycles + SCAN_PERIOD_CYCLES;
    return true;
}

bool hal_adc_scan_select(hal_board *board, uint16_t channel_mask)
{
    if (board->adc_scan_mask == 0 || !scan_mask_supported(channel_mask))
        return false;
    board->adc_scan_mask = channel_mask;
    return true;
}

void hal_adc_scan_stop(hal_board *board)
{
    board->adc_scan_mask = 0;
    board->adc_scan_callback = 0;
}

void host_board_run_adc_scan(hal_board *board);

void host_board_run_adc_scan(hal_board *board)
{
    uint16_t values[HAL_ADC_SCAN_MAX_CHANNELS];
    uint8_t count = 0;
    uint8_t channel;

    board->adc_next_due += SCAN_PERIOD_CYCLES;
    for (channel = 0; channel < HAL_ADC_CHANNEL_COUNT; channel++) {
        if ((board->adc_scan_mask >> channel) & 1u)
            values[count++] = board->world->adc_read(board->world->context, channel, board->cycles);
    }
    if (board->adc_scan_callback)
        board->adc_scan_callback(board->adc_scan_context, values, count);
}

void hal_pin_write(hal_board *board, hal_pin pin, bool high)
{
    if ((uint16_t)pin >= HAL_PIN_FIRST_INPUT)
        return;
    board->outputs[pin] = high;
    board->world->pin_written(board->world->context, pin, high, board->cycles);
}

bool hal_pin_read(hal_board *board, hal_pin pin)
{
    if ((uint16_t)pin >= HAL_PIN_COUNT)
        return false;
    if (pin < HAL_PIN_FIRST_INPUT)
        return board->outputs[pin];
    return board->world->pin_read(board->world->context, pin, board->cycles);
}

bool hal_pin_watch_falling_edge(hal_board *board, hal_pin pin, hal_callback callback, void *context)
{
    // As on the chip, only the remote receiver's line has an edge interrupt.
    if (pin != HAL_PIN_REMOTE)
        return false;
    board->edge_callback[pin] = callback;
    board->edge_context[pin] = context;
    board->last_input[pin] = hal_pin_read(board, pin);
    return true;
}

void hal_pin_unwatch(hal_board *board, hal_pin pin)
{
    if ((uint16_t)pin < HAL_PIN_COUNT)
        board->edge_callback[pin] = 0;
}

void host_board_input_changed(hal_board *board, hal_pin pin)
{
    bool level;

    if ((uint16_t)pin < HAL_PIN_FIRST_INPUT || (uint16_t)pin >= HAL_PIN_COUNT)
        return;
    level = hal_pin_read(board, pin);
    if (board->last_input[pin] && !level && board->edge_callback[pin])
        board->edge_callback[pin](board->edge_context[pin]);
    board->last_input[pin] = level;
}

bool hal_i2c_write(hal_board *board,
                   uint8_t device,
                   uint8_t reg,
                   const uint8_t *bytes,
                   uint16_t count)
{
    return board->world->i2c_write(board->world->context, device, reg, bytes, count);
}

bool hal_i2c_read(hal_board *board, uint8_t device, uint8_t reg, uint8_t *bytes, uint16_t count)
{
    return board->world->i2c_read(board->world->context, device, reg, bytes, count);
}

bool hal_camera_read_row(hal_board *board, uint16_t row, uint8_t *bytes, uint16_t count)
{
    uint16_t i;
    for (i = 0; i < count; i++)
        bytes[i] = board->world->camera_byte(board->world->context, row, i, board->cycles);
    return true;
}
