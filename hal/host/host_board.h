// A simulated e-puck board on a PC: the hal.h functions over plain memory.
//
// The host program owns the board and drives it: it sets the board's clock
// (real or simulated time), puts received bytes in, and takes the bytes the
// firmware sends through a callback. Nothing here touches the operating
// system, so tests and the simulator can wire boards together as they like.

#ifndef HOST_BOARD_H
#define HOST_BOARD_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/hal.h"

// Bytes the link can hold before the firmware reads them: two whole frames,
// as a UART ring large enough for a full frame (protocol.md §2) would.
#define HOST_LINK_RECEIVE_CAPACITY 1044

struct hal_board {
    uint32_t milliseconds;
    uint8_t receive[HOST_LINK_RECEIVE_CAPACITY];
    uint16_t receive_start;
    uint16_t receive_count;
    // Where the firmware's bytes go; called from hal_link_send.
    void (*link_output)(void *context, const uint8_t *bytes, uint16_t count);
    void *link_context;
};

// Prepares a board at time 0 with an empty link whose output goes to
// `link_output` (which may be NULL to drop it).
void host_board_init(hal_board *board,
                     void (*link_output)(void *context, const uint8_t *bytes, uint16_t count),
                     void *link_context);

// Sets the board's clock; time never goes backwards.
void host_board_set_time(hal_board *board, uint32_t milliseconds);

// Bytes the link can still take.
uint16_t host_board_link_room(const hal_board *board);

// Puts received bytes on the link; returns false, taking nothing, when they
// do not all fit.
bool host_board_link_deliver(hal_board *board, const uint8_t *bytes, uint16_t count);

#endif
