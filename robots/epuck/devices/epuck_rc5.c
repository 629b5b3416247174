// RC5 decoding from the falling edge that starts a frame, as the library
// does it (§3.9), with EPUCK_TIMER_SPARE instead of its 0.1 ms agenda ticks.

#include "epuck_rc5.h"

// From the first falling edge to the check of the second start bit, then to
// the first sample (the toggle bit), then between samples (§3.9), so that
// samples fall in the first half of each bit. The library samples every
// 1.8 ms, its 0.1 ms agenda's nearest to an RC5 bit (64 periods of the 36
// kHz carrier, 1.778 ms); it drifts 22 µs a bit, 0.24 ms by the last one,
// which left too little room for an interrupt's delay on the chip (the
// arena's dsPIC robots read the last bits wrong): the bit itself is used.
#define CHECK_DELAY_US     2100u
#define FIRST_SAMPLE_US    900u
#define SAMPLE_INTERVAL_US 1778u
#define TOGGLE_BITS        1u
#define ADDRESS_BITS       5u
#define COMMAND_BITS       6u
#define FRAME_SAMPLES      (TOGGLE_BITS + ADDRESS_BITS + COMMAND_BITS)
#define ADDRESS_MASK       0x1Fu
#define COMMAND_MASK       0x3Fu

static void falling_edge(void *context);

static void listen(epuck_rc5 *rc5)
{
    epuck_board_pin_watch_falling_edge(rc5->board, EPUCK_PIN_REMOTE, falling_edge, rc5);
}

static void sample(void *context)
{
    epuck_rc5 *rc5 = context;
    bool high = epuck_board_pin_read(rc5->board, EPUCK_PIN_REMOTE);

    if (rc5->checking) {
        rc5->checking = false;
        if (high) { // not a start bit: noise
            epuck_board_timer_stop(rc5->board, EPUCK_TIMER_SPARE);
            listen(rc5);
            return;
        }
        epuck_board_timer_start(rc5->board, EPUCK_TIMER_SPARE, FIRST_SAMPLE_US, sample, rc5);
        return;
    }
    if (rc5->bits_left == FRAME_SAMPLES)
        epuck_board_timer_start(rc5->board, EPUCK_TIMER_SPARE, SAMPLE_INTERVAL_US, sample, rc5);
    rc5->shift = (uint16_t)((rc5->shift << 1) | (high ? 1u : 0u));
    rc5->bits_left--;
    if (rc5->bits_left != 0)
        return;
    epuck_board_timer_stop(rc5->board, EPUCK_TIMER_SPARE);
    rc5->command = (uint8_t)(rc5->shift & COMMAND_MASK);
    rc5->address = (uint8_t)((rc5->shift >> COMMAND_BITS) & ADDRESS_MASK);
    rc5->toggle = (uint8_t)((rc5->shift >> (COMMAND_BITS + ADDRESS_BITS)) & 1u);
    rc5->received = true;
    listen(rc5);
}

static void falling_edge(void *context)
{
    epuck_rc5 *rc5 = context;

    // The edges inside the frame are sampled, not signalled.
    epuck_board_pin_unwatch(rc5->board, EPUCK_PIN_REMOTE);
    rc5->checking = true;
    rc5->bits_left = FRAME_SAMPLES;
    rc5->shift = 0;
    epuck_board_timer_start(rc5->board, EPUCK_TIMER_SPARE, CHECK_DELAY_US, sample, rc5);
}

bool epuck_rc5_init(epuck_rc5 *rc5, hal_board *board)
{
    rc5->board = board;
    rc5->bits_left = 0;
    rc5->shift = 0;
    rc5->checking = false;
    rc5->received = false;
    rc5->toggle = 0;
    rc5->address = 0;
    rc5->command = 0;
    return epuck_board_pin_watch_falling_edge(board, EPUCK_PIN_REMOTE, falling_edge, rc5);
}

bool epuck_rc5_take(epuck_rc5 *rc5, uint8_t *toggle, uint8_t *address, uint8_t *command)
{
    hal_critical_state state;

    // Only the interrupt sets the flag, only this clears it: read clear
    // outside the critical section, it is as if the frame came just after;
    // read set, it stays set. The main loop (every millisecond) is spared
    // the section until a frame waits.
    if (!rc5->received)
        return false;
    state = hal_critical_enter(rc5->board);
    *toggle = rc5->toggle;
    *address = rc5->address;
    *command = rc5->command;
    rc5->received = false;
    hal_critical_leave(rc5->board, state);
    return true;
}
