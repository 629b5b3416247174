// The camera's pixel port (§3.5), polled: frame start on VSYNC, rows on
// HREF, one byte of PORTD's upper half per PCLK. Simple and slow; the
// library's interrupt-driven capture on T4/T5 can replace it later.

#include "dspic30_board.h"
#include "dspic30_registers.h"

#define CAMERA_DATA_SHIFT 8u // Y0..Y7 on RD8..RD15

// Waits until `pin` reads `level`; false on a timeout.
static bool wait_for(hal_board *board, hal_pin pin, bool level)
{
    uint32_t attempts;
    for (attempts = 0; attempts < DSPIC30_CAMERA_WAIT_ATTEMPTS; attempts++) {
        if (hal_pin_read(board, pin) == level)
            return true;
    }
    return false;
}

bool hal_camera_read_row(hal_board *board, uint16_t row, uint8_t *bytes, uint16_t count)
{
    const bool active = DSPIC30_CAMERA_SYNC_ACTIVE_LEVEL;
    const bool latch = DSPIC30_CAMERA_PCLK_LATCH_LEVEL;
    hal_critical_state state;
    uint16_t i;
    bool ok = true;

    // A whole frame: wait for VSYNC to end, then to begin.
    if (!wait_for(board, HAL_PIN_CAMERA_VSYNC, !active) ||
        !wait_for(board, HAL_PIN_CAMERA_VSYNC, active))
        return false;
    for (i = 0; i < row; i++) {
        if (!wait_for(board, HAL_PIN_CAMERA_HREF, active) ||
            !wait_for(board, HAL_PIN_CAMERA_HREF, !active))
            return false;
    }
    if (!wait_for(board, HAL_PIN_CAMERA_HREF, active))
        return false;
    // No interrupt may make us miss a pixel clock.
    state = hal_critical_enter(board);
    for (i = 0; i < count && ok; i++) {
        ok = wait_for(board, HAL_PIN_CAMERA_PCLK, !latch) &&
             wait_for(board, HAL_PIN_CAMERA_PCLK, latch);
        bytes[i] = (uint8_t)(dspic30_read(DSPIC30_PORTD) >> CAMERA_DATA_SHIFT);
    }
    hal_critical_leave(board, state);
    return ok;
}
