// The e-puck's digital pins (§3.1): each epuck_pin is a bit of one port, an
// output driven through LAT or an input read through PORT. The RC5
// receiver's falling edges come through INT0 (§3.9).

#include "dspic30_pin_map.h"
#include "epuck_dspic30_board.h"
#include "ports/dspic30/dspic30_registers.h"

typedef struct pin_location {
    uint16_t tris; // the port's TRIS register; PORT and LAT follow it
    uint8_t bit;
    bool output;
} pin_location;

#define OUT                                     true
#define IN                                      false
#define PIN_LOCATION(pin, port, bit, direction) [pin] = { DSPIC30_TRIS##port, bit, direction },

static const pin_location pin_map[EPUCK_PIN_COUNT] = { DSPIC30_EPUCK_PINS(PIN_LOCATION) };

// The camera's data bus: the upper byte of port D, inputs (§3.5).
#define CAMERA_DATA_BITS 0xFF00u

void dspic30_gpio_init(hal_board *board)
{
    uint16_t i;

    board->edge_callback = 0;
    board->edge_context = 0;
    // Outputs start low, as the library's port initialisation leaves them.
    for (i = 0; i < EPUCK_PIN_COUNT; i++) {
        const pin_location *pin = &pin_map[i];
        uint16_t mask = (uint16_t)(1u << pin->bit);
        if (pin->output) {
            dspic30_clear_bits((uint16_t)(pin->tris + DSPIC30_LAT_OFFSET), mask);
            dspic30_clear_bits(pin->tris, mask);
        } else {
            dspic30_set_bits(pin->tris, mask);
        }
    }
    dspic30_set_bits(DSPIC30_TRISD, CAMERA_DATA_BITS);

    // INT0 (the remote) on falling edges, enabled by a watch.
    dspic30_set_bits(DSPIC30_INTCON2, DSPIC30_INTCON2_INT0EP);
    dspic30_set_priority(DSPIC30_IPC_INT0, DSPIC30_SHIFT_INT0, DSPIC30_PRIORITY_REMOTE);
    dspic30_clear_bits(DSPIC30_IEC0, DSPIC30_IRQ0_INT0);
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_INT0);
}

void epuck_board_pin_write(hal_board *board, epuck_pin pin, bool high)
{
    const pin_location *location;
    uint16_t lat;

    (void)board;
    if ((uint16_t)pin >= EPUCK_PIN_COUNT || !pin_map[pin].output)
        return;
    location = &pin_map[pin];
    lat = (uint16_t)(location->tris + DSPIC30_LAT_OFFSET);
    if (high)
        dspic30_set_bits(lat, (uint16_t)(1u << location->bit));
    else
        dspic30_clear_bits(lat, (uint16_t)(1u << location->bit));
}

bool epuck_board_pin_read(hal_board *board, epuck_pin pin)
{
    const pin_location *location;
    uint16_t offset;

    (void)board;
    if ((uint16_t)pin >= EPUCK_PIN_COUNT)
        return false;
    location = &pin_map[pin];
    offset = location->output ? DSPIC30_LAT_OFFSET : DSPIC30_PORT_OFFSET;
    return (dspic30_read((uint16_t)(location->tris + offset)) >> location->bit) & 1u;
}

uint16_t epuck_board_pins_read(hal_board *board, epuck_pin first, uint8_t count)
{
    uint16_t levels = 0;
    uint8_t i;

    for (i = 0; i < count; i++)
        if (epuck_board_pin_read(board, (epuck_pin)(first + i)))
            levels = (uint16_t)(levels | (1u << i));
    return levels;
}

bool epuck_board_pin_watch_falling_edge(hal_board *board,
                                        epuck_pin pin,
                                        epuck_callback callback,
                                        void *context)
{
    if (pin != EPUCK_PIN_REMOTE)
        return false;
    dspic30_clear_bits(DSPIC30_IEC0, DSPIC30_IRQ0_INT0);
    board->edge_callback = callback;
    board->edge_context = context;
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_INT0);
    dspic30_set_bits(DSPIC30_IEC0, DSPIC30_IRQ0_INT0);
    return true;
}

void epuck_board_pin_unwatch(hal_board *board, epuck_pin pin)
{
    if (pin != EPUCK_PIN_REMOTE)
        return;
    dspic30_clear_bits(DSPIC30_IEC0, DSPIC30_IRQ0_INT0);
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_INT0);
    board->edge_callback = 0;
}

void dspic30_on_remote_edge(hal_board *board)
{
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_INT0);
    if (board->edge_callback)
        board->edge_callback(board->edge_context);
}
