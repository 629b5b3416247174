// The camera's pixel port (§3.5): Timer4 counts the rows on HREF (T4CK), and
// its interrupt reads the board's line at the camera's byte rate.
//
// Why so: the main loop must never wait for the camera. A frame lasts some
// 50 ms, and a main loop that watched the rows above the line go by moved
// no byte of UART1's receive ring meanwhile: the ring holds 45 ms of the
// link at 115,200 baud, and a burst of frames from another robot was lost
// (docs/dspic30-sim.md, the finding on a second robot's traffic). Instead, a main-loop step that
// sees the blank between two frames (VSYNC inactive: no row passes) starts
// Timer4 counting HREF's rising edges, and Timer4 interrupts as the row
// above the line begins. The interrupt waits for that row to end, with
// UART1, the ADC and the timers free to come in; then, with every
// interrupt masked, it catches the line's HREF and reads the line at 8
// cycles a byte (dspic30_camera_row.c), as the library's capture does: the
// horizontal blank and the line, about a quarter of a millisecond, less
// than UART1's 4-byte FIFO holds.
//
// The interrupt comes at the start of the row above the line, so line 0
// (with no row above it) is read as line 1: 1/120 of the picture lower.

#include "epuck_dspic30_board.h"
#include "ports/dspic30/dspic30_registers.h"

// The first line that has a row above it.
#define FIRST_READABLE_ROW 1u
// Timer4 starts at 1 and interrupts on the edge after it reaches PR4: with
// PR4 = row, on the row-th edge, the start of the row above the line (a
// period of 0, which would suit line 1 otherwise, never interrupts).
#define ROW_COUNT_START 1u
// Edges Timer4 counts after its interrupt while the line is read: the
// line's own, none of a later row.
#define EDGES_DURING_THE_READ 1u

static bool href_active(hal_board *board)
{
    return epuck_board_pin_read(board, EPUCK_PIN_CAMERA_HREF) ==
           (bool)DSPIC30_CAMERA_SYNC_ACTIVE_LEVEL;
}

static bool vsync_active(hal_board *board)
{
    return epuck_board_pin_read(board, EPUCK_PIN_CAMERA_VSYNC) ==
           (bool)DSPIC30_CAMERA_SYNC_ACTIVE_LEVEL;
}

static void stop_counting(void)
{
    dspic30_write(DSPIC30_T4CON, 0);
    dspic30_clear_bits(DSPIC30_IEC1, DSPIC30_IRQ1_T4);
    dspic30_clear_bits(DSPIC30_IFS1, DSPIC30_IRQ1_T4);
}

// Timer4 counting HREF from now on, to interrupt at the row above the line.
static void start_counting(const hal_board *board)
{
    stop_counting();
    dspic30_write(DSPIC30_TMR4, ROW_COUNT_START);
    dspic30_write(DSPIC30_PR4, board->camera_row);
    dspic30_set_bits(DSPIC30_IEC1, DSPIC30_IRQ1_T4);
    dspic30_write(DSPIC30_T4CON, DSPIC30_TCON_TON | DSPIC30_TCON_TCS); // 1:1, T4CK
}

void dspic30_camera_init(hal_board *board)
{
    board->camera_phase = DSPIC30_CAMERA_IDLE;
    board->camera_bytes = 0;
    stop_counting();
    dspic30_set_priority(DSPIC30_IPC_T4, DSPIC30_SHIFT_T4, DSPIC30_PRIORITY_CAMERA);
}

void epuck_board_camera_start(hal_board *board, uint16_t row, uint8_t *bytes, uint16_t pixels)
{
    stop_counting();
    board->camera_row = row < FIRST_READABLE_ROW ? FIRST_READABLE_ROW : row;
    board->camera_bytes = bytes;
    board->camera_pixels = pixels;
    board->camera_started_ms = hal_milliseconds(board);
    board->camera_phase = DSPIC30_CAMERA_WAITING_FOR_FRAME;
}

epuck_camera_step epuck_board_camera_step(hal_board *board)
{
    hal_critical_state state;
    dspic30_camera_phase phase;

    state = hal_critical_enter(board);
    if (board->camera_phase == DSPIC30_CAMERA_WAITING_FOR_FRAME && !vsync_active(board)) {
        start_counting(board);
        // Still between frames once Timer4 counts: it will see every row of
        // the next frame. Else try again at the next step.
        if (!vsync_active(board))
            board->camera_phase = DSPIC30_CAMERA_WAITING_FOR_ROW;
        else
            stop_counting();
    }
    hal_critical_leave(board, state);
    // The interrupt may end the read between these lines: read the phase
    // and give up a late one at once.
    state = hal_critical_enter(board);
    phase = board->camera_phase;
    if ((phase == DSPIC30_CAMERA_WAITING_FOR_FRAME || phase == DSPIC30_CAMERA_WAITING_FOR_ROW) &&
        hal_milliseconds(board) - board->camera_started_ms >= DSPIC30_CAMERA_FRAME_TIMEOUT_MS) {
        stop_counting();
        phase = DSPIC30_CAMERA_ROW_FAILED;
    }
    if (phase != DSPIC30_CAMERA_WAITING_FOR_FRAME && phase != DSPIC30_CAMERA_WAITING_FOR_ROW)
        board->camera_phase = DSPIC30_CAMERA_IDLE;
    hal_critical_leave(board, state);
    switch (phase) {
    case DSPIC30_CAMERA_WAITING_FOR_FRAME:
    case DSPIC30_CAMERA_WAITING_FOR_ROW: return EPUCK_CAMERA_READING;
    case DSPIC30_CAMERA_ROW_READ: return EPUCK_CAMERA_DONE;
    default: return EPUCK_CAMERA_FAILED;
    }
}

void dspic30_on_camera_row(hal_board *board)
{
    bool read = false;
    uint16_t poll;

    // One interrupt per read; Timer4 goes on counting for the check below.
    dspic30_clear_bits(DSPIC30_IEC1, DSPIC30_IRQ1_T4);
    dspic30_clear_bits(DSPIC30_IFS1, DSPIC30_IRQ1_T4);
    if (board->camera_phase != DSPIC30_CAMERA_WAITING_FOR_ROW) {
        stop_counting();
        return;
    }
    for (poll = 0; poll < DSPIC30_CAMERA_ROW_END_POLLS && href_active(board); poll++)
        ;
    if (!href_active(board)) {
        hal_critical_state state = hal_critical_enter(board);
        // Still in the blank before the line (nothing held this handler
        // past it), so the line is the next HREF.
        if (!href_active(board))
            read = dspic30_camera_read_row(
              board->camera_bytes, board->camera_pixels, DSPIC30_CAMERA_LINE_START_POLLS);
        hal_critical_leave(board, state);
    }
    // An interrupt that came a row late read the row below the line: Timer4
    // then saw two edges.
    read = read && dspic30_read(DSPIC30_TMR4) == EDGES_DURING_THE_READ;
    stop_counting();
    board->camera_phase = read ? DSPIC30_CAMERA_ROW_READ : DSPIC30_CAMERA_ROW_FAILED;
}
