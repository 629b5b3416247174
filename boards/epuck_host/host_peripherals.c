// The host board's e-puck peripherals (robots/epuck/epuck_board.h): ADC,
// pins, I2C and the camera's pixel port, each answered by the board's world
// at the board's current time.

#include "host_board.h"

uint16_t epuck_board_adc_read(hal_board *board, uint8_t channel)
{
    if (channel >= EPUCK_ADC_CHANNEL_COUNT || board->adc_scan_mask != 0)
        return 0;
    return board->world->adc_read(board->world->context, channel, board->cycles);
}

static uint8_t scan_channel_count(uint16_t mask)
{
    // The sequencer selects a scan's channels a thousand times a second:
    // without a population count instruction in the host's baseline,
    // __builtin_popcount is a call into libgcc. Bits counted in pairs,
    // nibbles, then bytes.
    uint16_t bits = (uint16_t)(mask - ((mask >> 1) & 0x5555u));
    bits = (uint16_t)((bits & 0x3333u) + ((bits >> 2) & 0x3333u));
    bits = (uint16_t)((bits + (bits >> 4)) & 0x0f0fu);
    return (uint8_t)((bits + (bits >> 8)) & 0x1fu);
}

static bool scan_count_supported(uint8_t count)
{
    return count >= EPUCK_ADC_SCAN_MIN_CHANNELS && count <= EPUCK_ADC_SCAN_MAX_CHANNELS;
}

bool epuck_board_adc_scan_start(hal_board *board,
                                uint16_t channel_mask,
                                epuck_adc_scan_callback callback,
                                void *context)
{
    uint8_t count = scan_channel_count(channel_mask);

    if (!scan_count_supported(count))
        return false;
    board->adc_scan_callback = callback;
    board->adc_scan_run_callback = 0;
    board->adc_scan_context = context;
    board->adc_scan_mask = channel_mask;
    board->adc_scan_channels = count;
    board->adc_next_due = board->cycles + HOST_ADC_SCAN_PERIOD_CYCLES;
    return true;
}

bool epuck_board_adc_scan_select(hal_board *board, uint16_t channel_mask)
{
    uint8_t count = scan_channel_count(channel_mask);

    if (board->adc_scan_mask == 0 || !scan_count_supported(count))
        return false;
    board->adc_scan_mask = channel_mask;
    board->adc_scan_channels = count;
    return true;
}

void epuck_board_adc_scan_stop(hal_board *board)
{
    board->adc_scan_mask = 0;
    board->adc_scan_callback = 0;
    board->adc_scan_run_callback = 0;
}

void epuck_board_adc_scan_runs(hal_board *board, epuck_adc_scan_run_callback callback)
{
    board->adc_scan_run_callback = callback;
}

void epuck_board_pin_write(hal_board *board, epuck_pin pin, bool high)
{
    if ((uint16_t)pin >= EPUCK_PIN_FIRST_INPUT)
        return;
    board->outputs[pin] = high;
    board->world->pin_written(board->world->context, pin, high, board->cycles);
}

bool epuck_board_pin_read(hal_board *board, epuck_pin pin)
{
    if ((uint16_t)pin >= EPUCK_PIN_COUNT)
        return false;
    if (pin < EPUCK_PIN_FIRST_INPUT)
        return board->outputs[pin];
    return board->world->pin_read(board->world->context, pin, board->cycles);
}

// Apart, so that the world's answer at once (every millisecond) costs no
// saving of the registers this loop needs.
__attribute__((noinline)) static uint16_t pins_read_one_by_one(hal_board *board,
                                                               epuck_pin first,
                                                               uint8_t count)
{
    uint16_t levels = 0;
    uint8_t i;

    for (i = 0; i < count; i++)
        if (epuck_board_pin_read(board, (epuck_pin)(first + i)))
            levels = (uint16_t)(levels | (1u << i));
    return levels;
}

uint16_t epuck_board_pins_read(hal_board *board, epuck_pin first, uint8_t count)
{
    const host_world *world = board->world;

    if (world->inputs_read && (uint16_t)first >= EPUCK_PIN_FIRST_INPUT &&
        (uint16_t)first + count <= EPUCK_PIN_COUNT)
        return world->inputs_read(world->context, first, count, board->cycles);
    return pins_read_one_by_one(board, first, count);
}

bool epuck_board_pin_watch_falling_edge(hal_board *board,
                                        epuck_pin pin,
                                        epuck_callback callback,
                                        void *context)
{
    // As on the chip, only the remote receiver's line has an edge interrupt.
    if (pin != EPUCK_PIN_REMOTE)
        return false;
    board->edge_callback[pin] = callback;
    board->edge_context[pin] = context;
    board->configuration_changes++;
    board->last_input[pin] = epuck_board_pin_read(board, pin);
    return true;
}

void epuck_board_pin_unwatch(hal_board *board, epuck_pin pin)
{
    if ((uint16_t)pin < EPUCK_PIN_COUNT)
        board->edge_callback[pin] = 0;
    board->configuration_changes++;
}

void host_board_input_changed(hal_board *board, epuck_pin pin)
{
    bool level;

    if ((uint16_t)pin < EPUCK_PIN_FIRST_INPUT || (uint16_t)pin >= EPUCK_PIN_COUNT)
        return;
    level = epuck_board_pin_read(board, pin);
    if (board->last_input[pin] && !level && board->edge_callback[pin])
        board->edge_callback[pin](board->edge_context[pin]);
    board->last_input[pin] = level;
}

bool epuck_board_i2c_write(hal_board *board,
                           uint8_t device,
                           uint8_t reg,
                           const uint8_t *bytes,
                           uint16_t count)
{
    return board->world->i2c_write(board->world->context, device, reg, bytes, count);
}

bool epuck_board_i2c_read(hal_board *board,
                          uint8_t device,
                          uint8_t reg,
                          uint8_t *bytes,
                          uint16_t count)
{
    return board->world->i2c_read(board->world->context, device, reg, bytes, count);
}

void epuck_board_camera_start(hal_board *board, uint16_t row, uint8_t *bytes, uint16_t pixels)
{
    board->camera_bytes = bytes;
    board->camera_row = row;
    board->camera_pixels = pixels;
}

epuck_camera_step epuck_board_camera_step(hal_board *board)
{
    uint16_t i;

    // The world's camera answers at once: the row is read at the first step.
    if (board->camera_bytes == 0)
        return EPUCK_CAMERA_FAILED;
    if (board->world->camera_every_second_pixel) {
        board->world->camera_every_second_pixel(board->world->context,
                                                board->camera_row,
                                                board->camera_pixels,
                                                board->cycles,
                                                board->camera_bytes);
        board->camera_bytes = 0;
        return EPUCK_CAMERA_DONE;
    }
    // Every second pixel: its bytes are the row's 2 × EPUCK_CAMERA_PIXEL_BYTES × p onwards.
    for (i = 0; i < board->camera_pixels * EPUCK_CAMERA_PIXEL_BYTES; i++) {
        uint16_t pixel = (uint16_t)(i / EPUCK_CAMERA_PIXEL_BYTES);
        uint16_t in_row =
          (uint16_t)(2u * pixel * EPUCK_CAMERA_PIXEL_BYTES + i % EPUCK_CAMERA_PIXEL_BYTES);
        board->camera_bytes[i] = board->world->camera_byte(
          board->world->context, board->camera_row, in_row, board->cycles);
    }
    board->camera_bytes = 0;
    return EPUCK_CAMERA_DONE;
}
