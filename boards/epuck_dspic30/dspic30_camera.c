// The camera's pixel port (§3.5), polled, in steps: frame start on VSYNC,
// rows on HREF, one byte of PORTD's upper half per PCLK.
//
// Each step watches VSYNC for a few hundred microseconds (the main loop
// goes on meanwhile): the rows can only be counted from the very start of a
// frame, so a step that sees the frame begin reads the rows above the line
// and the line at once. That part still takes up to a frame time for the
// bottom line; counting HREF with an interrupt (as the library's capture on
// T4/T5 does) would remove it.

#include "epuck_dspic30_board.h"
#include "ports/dspic30/dspic30_registers.h"

#define CAMERA_DATA_SHIFT 8u // Y0..Y7 on RD8..RD15
// A pixel kept and the one skipped after it.
#define PIXEL_PAIR_BYTES (2u * EPUCK_CAMERA_PIXEL_BYTES)

// Waits until `pin` reads `level`; false on a timeout.
static bool wait_for(hal_board *board, epuck_pin pin, bool level)
{
    uint32_t attempts;
    for (attempts = 0; attempts < DSPIC30_CAMERA_WAIT_ATTEMPTS; attempts++) {
        if (epuck_board_pin_read(board, pin) == level)
            return true;
    }
    return false;
}

// Reads the board's row from a frame that has just begun.
static bool read_row(hal_board *board)
{
    const bool active = DSPIC30_CAMERA_SYNC_ACTIVE_LEVEL;
    const bool latch = DSPIC30_CAMERA_PCLK_LATCH_LEVEL;
    // Bytes up to the end of the last pixel kept: the pixel skipped after it
    // is not waited for.
    const uint16_t clocked = board->camera_pixels == 0
                               ? 0
                               : (uint16_t)(board->camera_pixels * PIXEL_PAIR_BYTES -
                                            (PIXEL_PAIR_BYTES - EPUCK_CAMERA_PIXEL_BYTES));
    uint8_t *kept = board->camera_bytes;
    hal_critical_state state;
    uint16_t i;
    bool ok = true;

    for (i = 0; i < board->camera_row; i++) {
        if (!wait_for(board, EPUCK_PIN_CAMERA_HREF, active) ||
            !wait_for(board, EPUCK_PIN_CAMERA_HREF, !active))
            return false;
    }
    if (!wait_for(board, EPUCK_PIN_CAMERA_HREF, active))
        return false;
    // No interrupt may make us miss a pixel clock. Every byte of the row up
    // to the last pixel kept is clocked in; those of the pixels between are
    // not kept.
    state = hal_critical_enter(board);
    for (i = 0; i < clocked && ok; i++) {
        uint8_t byte;
        ok = wait_for(board, EPUCK_PIN_CAMERA_PCLK, !latch) &&
             wait_for(board, EPUCK_PIN_CAMERA_PCLK, latch);
        byte = (uint8_t)(dspic30_read(DSPIC30_PORTD) >> CAMERA_DATA_SHIFT);
        if (i % PIXEL_PAIR_BYTES < EPUCK_CAMERA_PIXEL_BYTES)
            *kept++ = byte;
    }
    hal_critical_leave(board, state);
    return ok;
}

void epuck_board_camera_start(hal_board *board, uint16_t row, uint8_t *bytes, uint16_t pixels)
{
    board->camera_row = row;
    board->camera_bytes = bytes;
    board->camera_pixels = pixels;
    board->camera_started_ms = hal_milliseconds(board);
    board->camera_phase = DSPIC30_CAMERA_WAITING_FOR_FRAME;
}

epuck_camera_step epuck_board_camera_step(hal_board *board)
{
    const bool active = DSPIC30_CAMERA_SYNC_ACTIVE_LEVEL;
    bool seen_gap = false; // VSYNC inactive seen during this step
    uint16_t poll;

    if (board->camera_phase != DSPIC30_CAMERA_WAITING_FOR_FRAME)
        return EPUCK_CAMERA_FAILED;
    // A frame begins when VSYNC turns active after this step saw it
    // inactive: a start between two steps is missed, not miscounted.
    for (poll = 0; poll < DSPIC30_CAMERA_STEP_POLLS; poll++) {
        bool level = epuck_board_pin_read(board, EPUCK_PIN_CAMERA_VSYNC);
        if (level != active) {
            seen_gap = true;
        } else if (seen_gap) {
            board->camera_phase = DSPIC30_CAMERA_IDLE;
            return read_row(board) ? EPUCK_CAMERA_DONE : EPUCK_CAMERA_FAILED;
        }
    }
    if (hal_milliseconds(board) - board->camera_started_ms >= DSPIC30_CAMERA_FRAME_TIMEOUT_MS) {
        board->camera_phase = DSPIC30_CAMERA_IDLE;
        return EPUCK_CAMERA_FAILED;
    }
    return EPUCK_CAMERA_READING;
}
