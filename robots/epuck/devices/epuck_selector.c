// The selector's four bits, read raw as the library does.

#include "epuck_selector.h"

#define SELECTOR_BITS 4u

// ⚠ Pull-ups and polarity of the selector are not documented (§3.8); the
// library reads the raw levels as the position, so a high pin is a 1 bit.
#define EPUCK_SELECTOR_ACTIVE_HIGH 1

uint16_t epuck_selector_read(hal_board *board)
{
    uint16_t levels = epuck_board_pins_read(board, EPUCK_PIN_SELECTOR_0, SELECTOR_BITS);

    return (uint16_t)(EPUCK_SELECTOR_ACTIVE_HIGH ? levels : ~levels & ((1u << SELECTOR_BITS) - 1u));
}

uint16_t epuck_selector_node_id(uint16_t position)
{
    return (uint16_t)((position & EPUCK_SELECTOR_NODE_MASK) + 1u);
}
