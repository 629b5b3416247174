// Camera: reset, identification, the register writes of the fact sheet
// (§3.5) with our window and format, and RGB565 decoding of one row.

#include "epuck_camera.h"

#define REGISTER_ID_HIGH 0x00u
#define ID_HIGH_PO3030   0x30u
#define ID_HIGH_PO6030   0x60u
#define ID_LOW           0x30u

// The reset pulse: the library holds RESET low for about 100 instructions
// (§3.5), some 7 µs; 10 µs is safely longer.
#define RESET_PULSE_US 10u

// ⚠ The frame rate was never measured (§6.2); lines are read at most this
// often, which also keeps the host (where a read does not wait for a frame)
// from raising `camera` on every loop.
#define EPUCK_CAMERA_FRAME_INTERVAL_MS 50u

#define PERCENT 100

// Scaling of the RGB565 fields to the upstream firmware's ranges (§3.5).
#define RED_BLUE_SCALE    3
#define GREEN_SCALE_TIMES 3
#define GREEN_SCALE_OVER  2
// A pixel's bytes are read into one word of the line (epuck_camera_capture).
typedef char pixel_fits_a_word[EPUCK_CAMERA_PIXEL_BYTES == sizeof(int16_t) ? 1 : -1];

// The sensor's usable array starts at these coordinates (§3.5), and our
// window skips EPUCK_WINDOW_LEFT columns of it (the GCtronic line, §6.1).
#define PO3030_ORIGIN_X 210u
#define PO3030_ORIGIN_Y 7u
#define PO6030_ORIGIN_X 80u
#define WINDOW_LEFT     80u
#define WINDOW_WIDTH    480u
#define WINDOW_HEIGHT   480u

typedef struct register_value {
    uint8_t reg;
    uint8_t value;
} register_value;

#define HIGH_BYTE(x) ((uint8_t)((x) >> 8))
#define LOW_BYTE(x)  ((uint8_t)((x)&0xFFu))

#define PO3030_X1 (PO3030_ORIGIN_X + WINDOW_LEFT)
#define PO3030_X2 (PO3030_X1 + WINDOW_WIDTH)
#define PO3030_Y1 PO3030_ORIGIN_Y
#define PO3030_Y2 (PO3030_Y1 + WINDOW_HEIGHT)

// ⚠ The library writes the frame height registers with the width value
// (§3.5); we keep its value, as robots were tested with it.
#define EPUCK_PO3030_FRAME_HEIGHT 0x0353u
#define PO3030_FRAME_WIDTH        0x0353u
// ⚠ The clock divider: the library's table value (/128); its per-mode
// values (§3.5) are not decoded with certainty.
#define EPUCK_PO3030_SPEED    0x70u
#define PO3030_SAMPLING_QQVGA 0x33u
#define PO3030_FORMAT_RGB565  0x08u

// The PO3030K table of the library (§3.5), with our window, format and
// subsampling; registers whose values the fact sheet does not give (gamma,
// colour matrix, sepia tone, exposure limits) keep the sensor's defaults.
static const register_value po3030_registers[] = {
    { 0x04, HIGH_BYTE(PO3030_FRAME_WIDTH) },
    { 0x05, LOW_BYTE(PO3030_FRAME_WIDTH) },
    { 0x06, HIGH_BYTE(EPUCK_PO3030_FRAME_HEIGHT) },
    { 0x07, LOW_BYTE(EPUCK_PO3030_FRAME_HEIGHT) },
    { 0x08, HIGH_BYTE(PO3030_X1) },
    { 0x09, LOW_BYTE(PO3030_X1) },
    { 0x0A, HIGH_BYTE(PO3030_Y1) },
    { 0x0B, LOW_BYTE(PO3030_Y1) },
    { 0x0C, HIGH_BYTE(PO3030_X2) },
    { 0x0D, LOW_BYTE(PO3030_X2) },
    { 0x0E, HIGH_BYTE(PO3030_Y2) },
    { 0x0F, LOW_BYTE(PO3030_Y2) },
    { 0x12, 0x02 }, // bias
    { 0x13, 0x02 },
    { 0x15, 0x10 }, // colour gains
    { 0x16, 0x40 },
    { 0x17, 0x40 },
    { 0x18, 0x40 },
    { 0x19, 0x40 },
    { 0x1A, 0x03 }, // integration time
    { 0x1B, 0xE6 },
    { 0x1C, 0x00 },
    { 0x1D, EPUCK_PO3030_SPEED },
    { 0x1E, 0x0A }, // no mirroring
    { 0x1F, 0x1B },
    { 0x20, PO3030_SAMPLING_QQVGA },
    { 0x3B, 0x00 }, // ADC offset
    { 0x46, 0x80 }, // flicker mode
    { 0x48, 0x60 }, // flicker period
    { 0x49, 0x96 },
    { 0x4A, 0x00 },
    { 0x4B, 0x7D },
    { 0x4C, 0x00 },
    { 0x4E, PO3030_FORMAT_RGB565 },
    { 0x4F, 0x0A }, // sepia
    { 0x50, 0x70 },
    { 0x59, 0x00 }, // lens gain
    { 0x5A, 0x00 },
    { 0x5B, 0x00 },
    { 0x5C, 0xAC }, // edge
    { 0x5D, 0x02 },
    { 0x97, 0x25 }, // Cb/Cr gain
    { 0x98, 0x25 },
    { 0x9B, 0x00 }, // brightness, contrast
    { 0x9C, 0x96 },
    { 0xA5, HIGH_BYTE(PO3030_Y1) }, // VSYNC start and stop rows, column
    { 0xA6, LOW_BYTE(PO3030_Y1) },
    { 0xA7, HIGH_BYTE(PO3030_Y2) },
    { 0xA8, LOW_BYTE(PO3030_Y2) },
    { 0xA9, 0x00 },
    { 0xAA, 0x01 },
    { 0xD4, 0x3C }, // AWB and AE on
    { 0xD5, 0x01 },
    { 0xD8, 0x80 }, // gamma select
};

// PO6030K (§3.5): register 0x03 selects the bank of the registers after it.
#define PO6030_BANK_REGISTER 0x03u
#define PO6030_BANK_A        0x00u
#define PO6030_BANK_B        0x01u
#define PO6030_X_START       (PO6030_ORIGIN_X + WINDOW_LEFT)

static const register_value po6030_registers[] = {
    { PO6030_BANK_REGISTER, PO6030_BANK_B },
    { 0x38, 0x08 }, // RGB565
    { 0x80, 0x80 }, // scale X: QQVGA
    { 0x81, 0x80 }, // scale Y: QQVGA
    { 0x82, 0x01 },
    { 0x68, 0x03 }, // pixel clock divider, colour QQVGA
    { 0x50, HIGH_BYTE(PO6030_X_START) },
    { 0x51, LOW_BYTE(PO6030_X_START) },
    { PO6030_BANK_REGISTER, PO6030_BANK_A },
    { 0x90, 0xC0 }, // mirror (1, 1), as at the library's init
};

static bool write_table(hal_board *board, const register_value *table, uint16_t count)
{
    uint16_t i;

    for (i = 0; i < count; i++) {
        if (!epuck_board_i2c_write(
              board, EPUCK_I2C_CAMERA_ADDRESS, table[i].reg, &table[i].value, 1))
            return false;
    }
    return true;
}

bool epuck_camera_init(epuck_camera *camera, hal_board *board)
{
    uint8_t id[2];
    bool written = false;

    camera->board = board;
    camera->model = EPUCK_CAMERA_NONE;
    camera->captured = false;
    camera->reading = false;
    camera->last_capture_ms = 0;
    epuck_board_pin_write(board, EPUCK_PIN_CAMERA_RESET, false);
    hal_delay_microseconds(board, RESET_PULSE_US);
    epuck_board_pin_write(board, EPUCK_PIN_CAMERA_RESET, true);
    if (!epuck_board_i2c_read(board, EPUCK_I2C_CAMERA_ADDRESS, REGISTER_ID_HIGH, id, sizeof id) ||
        id[1] != ID_LOW)
        return false;
    if (id[0] == ID_HIGH_PO3030)
        written = write_table(
          board, po3030_registers, sizeof po3030_registers / sizeof po3030_registers[0]);
    else if (id[0] == ID_HIGH_PO6030)
        written = write_table(
          board, po6030_registers, sizeof po6030_registers / sizeof po6030_registers[0]);
    if (!written)
        return false;
    camera->model = id[0] == ID_HIGH_PO3030 ? EPUCK_CAMERA_PO3030 : EPUCK_CAMERA_PO6030;
    return true;
}

epuck_camera_model epuck_camera_model_of(const epuck_camera *camera)
{
    return camera->model;
}

bool epuck_camera_capture(epuck_camera *camera,
                          int16_t line_percent,
                          int16_t *red,
                          int16_t *green,
                          int16_t *blue)
{
    uint32_t now = hal_milliseconds(camera->board);
    epuck_camera_step step;
    uint16_t i;

    if (camera->model == EPUCK_CAMERA_NONE)
        return false;
    if (!camera->reading) {
        uint16_t row;
        if (camera->captured && now - camera->last_capture_ms < EPUCK_CAMERA_FRAME_INTERVAL_MS)
            return false;
        if (line_percent < 0)
            line_percent = 0;
        if (line_percent > PERCENT - 1)
            line_percent = PERCENT - 1;
        row = (uint16_t)((uint16_t)line_percent * EPUCK_CAMERA_WINDOW_ROWS / PERCENT);
        // The row's bytes go into `blue`, EPUCK_CAMERA_PIXEL_BYTES per word, so
        // that pixel i lies in blue[i] until the line replaces it below.
        epuck_board_camera_start(camera->board, row, (uint8_t *)blue, EPUCK_CAMERA_LINE_PIXELS);
        camera->reading = true;
    }
    step = epuck_board_camera_step(camera->board);
    if (step == EPUCK_CAMERA_READING)
        return false;
    // Done or failed, the next read waits for the interval.
    camera->reading = false;
    camera->captured = true;
    camera->last_capture_ms = now;
    if (step == EPUCK_CAMERA_FAILED)
        return false;
    for (i = 0; i < EPUCK_CAMERA_LINE_PIXELS; i++) {
        // The sensor sends R5G3 then G3B5 (§3.5).
        const uint8_t *pixel = (const uint8_t *)&blue[i];
        uint8_t first = pixel[0];
        uint8_t second = pixel[1];
        uint16_t r = (uint16_t)(first >> 3);
        uint16_t g = (uint16_t)(((first & 0x7u) << 3) | (second >> 5));
        uint16_t b = (uint16_t)(second & 0x1Fu);
        red[i] = (int16_t)(r * RED_BLUE_SCALE);
        green[i] = (int16_t)(g * GREEN_SCALE_TIMES / GREEN_SCALE_OVER);
        blue[i] = (int16_t)(b * RED_BLUE_SCALE);
    }
    return true;
}
