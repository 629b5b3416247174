// The 16-position rotary selector (hardware §3.8) on four input pins.

#ifndef EPUCK_SELECTOR_H
#define EPUCK_SELECTOR_H

#include <stdint.h>

#include "epuck_board.h"

#define EPUCK_SELECTOR_POSITIONS 16u

// The selector's position 0..15: bit n is selector pin n, read as it is
// (⚠ EPUCK_SELECTOR_ACTIVE_HIGH).
uint16_t epuck_selector_read(hal_board *board);

#endif
