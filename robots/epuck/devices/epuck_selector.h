// The 16-position rotary selector (hardware §3.8) on four input pins.

#ifndef EPUCK_SELECTOR_H
#define EPUCK_SELECTOR_H

#include <stdint.h>

#include "robots/epuck/epuck_board.h"

#define EPUCK_SELECTOR_POSITIONS 16u

// The selector's position 0..15: bit n is selector pin n, read as it is
// (⚠ EPUCK_SELECTOR_ACTIVE_HIGH).
uint16_t epuck_selector_read(hal_board *board);

// The node id of an e-puck whose stored settings give none (store_node_id):
// (position & EPUCK_SELECTOR_NODE_MASK) + 1, 1..8 (hardware §6.1, §6.6).
#define EPUCK_SELECTOR_NODE_MASK 0x7u
uint16_t epuck_selector_node_id(uint16_t position);

#endif
