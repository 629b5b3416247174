// The TV-remote receiver (hardware §3.9): RC5 frames decoded by timing. The
// receiver's output idles high and goes low while it sees the carrier; a
// falling edge (the middle of the first start bit) starts the decoding,
// which then samples the line on EPUCK_TIMER_SPARE: once to check the second
// start bit, then the first half of each of the toggle, 5 address and 6
// command bits, in which a high line is a 1 (RC5 Manchester code: a 1 is a
// half bit without carrier, then one with).

#ifndef EPUCK_RC5_H
#define EPUCK_RC5_H

#include <stdbool.h>
#include <stdint.h>

#include "robots/epuck/epuck_board.h"

typedef struct epuck_rc5 {
    hal_board *board;
    uint8_t bits_left; // bits still to sample; 0 between frames
    uint16_t shift;    // the bits sampled so far, first in the highest place
    bool checking;     // the next sample checks the second start bit
    // The last frame decoded.
    bool received; // a frame arrived since the last take
    uint8_t toggle;
    uint8_t address;
    uint8_t command;
} epuck_rc5;

// Starts listening to the remote receiver; returns false when the board
// cannot signal its edges.
bool epuck_rc5_init(epuck_rc5 *rc5, hal_board *board);

// When a frame arrived since the last call, gives its toggle bit (0/1),
// address (0..31) and command (0..63) and returns true; otherwise false.
bool epuck_rc5_take(epuck_rc5 *rc5, uint8_t *toggle, uint8_t *address, uint8_t *command);

#endif
