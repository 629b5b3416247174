// The camera (hardware §3.5): a PixelPlus PO3030K or PO6030K on I2C, set up
// for RGB565 at a quarter of its resolution in each direction (the sensor
// subsamples itself), over a window 480 pixels wide. A line is one row of
// that window, 120 pixels, of which every second one is kept: 60 pixels,
// split into red and blue (0..93) and green (0..94) as the upstream
// firmware scales them (§3.5).

#ifndef EPUCK_CAMERA_H
#define EPUCK_CAMERA_H

#include <stdbool.h>
#include <stdint.h>

#include "robots/epuck/epuck_board.h"

#define EPUCK_CAMERA_LINE_PIXELS 60u
// Rows of the window the line can be taken from.
#define EPUCK_CAMERA_WINDOW_ROWS 120u
// Pixels the sensor sends per row of the window; the line keeps every
// second one (epuck_board_camera_start).
#define EPUCK_CAMERA_ROW_PIXELS 120u

typedef enum epuck_camera_model {
    EPUCK_CAMERA_NONE, // no camera answered
    EPUCK_CAMERA_PO3030,
    EPUCK_CAMERA_PO6030
} epuck_camera_model;

typedef struct epuck_camera {
    hal_board *board;
    epuck_camera_model model;
    uint32_t last_capture_ms;
    bool captured; // at least one line read (or failed)
    bool reading;  // a row read is under way on the board
} epuck_camera;

// Resets the camera, identifies it by its registers 0x00/0x01 and writes its
// configuration; returns false (model EPUCK_CAMERA_NONE) when no known
// camera answers or a write fails.
bool epuck_camera_init(epuck_camera *camera, hal_board *board);

// The camera found at init.
epuck_camera_model epuck_camera_model_of(const epuck_camera *camera);

// Reads lines in steps, one per call, never waiting for a frame: when a
// camera is present and at least EPUCK_CAMERA_FRAME_INTERVAL_MS have passed
// since the last line, starts reading the line at `line_percent` (0..99,
// clamped) of the image height; when a read finishes, writes the line into
// `red`, `green`, `blue` (EPUCK_CAMERA_LINE_PIXELS each) and returns true.
// Otherwise returns false, writing nothing, except when the camera stops
// in the middle of a row: `blue`, where the row's bytes are read (the
// driver keeps no row of its own), then holds those read so far. A failed
// read waits for the interval too. Pass the same arrays until a read ends.
bool epuck_camera_capture(epuck_camera *camera,
                          int16_t line_percent,
                          int16_t *red,
                          int16_t *green,
                          int16_t *blue);

#endif
