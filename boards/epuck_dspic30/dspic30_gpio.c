// The e-puck's digital pins (§3.1): each epuck_pin is a bit of one port, an
// output driven through LAT or an input read through PORT. The RC5
// receiver's falling edges come through INT0 (§3.9).

#include "epuck_dspic30_board.h"
#include "ports/dspic30/dspic30_registers.h"

typedef struct pin_location {
    uint16_t tris; // the port's TRIS register; PORT and LAT follow it
    uint8_t bit;
    bool output;
} pin_location;

#define OUT true
#define IN  false

static const pin_location pin_map[EPUCK_PIN_COUNT] = {
    [EPUCK_PIN_LED_0] = { DSPIC30_TRISA, 6, OUT },
    [EPUCK_PIN_LED_1] = { DSPIC30_TRISA, 7, OUT },
    [EPUCK_PIN_LED_2] = { DSPIC30_TRISA, 9, OUT },
    [EPUCK_PIN_LED_3] = { DSPIC30_TRISA, 12, OUT },
    [EPUCK_PIN_LED_4] = { DSPIC30_TRISA, 10, OUT },
    [EPUCK_PIN_LED_5] = { DSPIC30_TRISA, 13, OUT },
    [EPUCK_PIN_LED_6] = { DSPIC30_TRISA, 14, OUT },
    [EPUCK_PIN_LED_7] = { DSPIC30_TRISA, 15, OUT },
    [EPUCK_PIN_FRONT_LED] = { DSPIC30_TRISC, 1, OUT },
    // ⚠ The library also names RC2 CAM_PWDN but never drives it so (§3.1).
    [EPUCK_PIN_BODY_LED] = { DSPIC30_TRISC, 2, OUT },
    [EPUCK_PIN_MOTOR_LEFT_A] = { DSPIC30_TRISD, 0, OUT },
    [EPUCK_PIN_MOTOR_LEFT_B] = { DSPIC30_TRISD, 1, OUT },
    [EPUCK_PIN_MOTOR_LEFT_C] = { DSPIC30_TRISD, 2, OUT },
    [EPUCK_PIN_MOTOR_LEFT_D] = { DSPIC30_TRISD, 3, OUT },
    [EPUCK_PIN_MOTOR_RIGHT_A] = { DSPIC30_TRISD, 4, OUT },
    [EPUCK_PIN_MOTOR_RIGHT_B] = { DSPIC30_TRISD, 5, OUT },
    [EPUCK_PIN_MOTOR_RIGHT_C] = { DSPIC30_TRISD, 6, OUT },
    [EPUCK_PIN_MOTOR_RIGHT_D] = { DSPIC30_TRISD, 7, OUT },
    [EPUCK_PIN_IR_PULSE_0_4] = { DSPIC30_TRISF, 7, OUT },
    [EPUCK_PIN_IR_PULSE_1_5] = { DSPIC30_TRISF, 8, OUT },
    [EPUCK_PIN_IR_PULSE_2_6] = { DSPIC30_TRISG, 0, OUT },
    [EPUCK_PIN_IR_PULSE_3_7] = { DSPIC30_TRISG, 1, OUT },
    [EPUCK_PIN_CAMERA_RESET] = { DSPIC30_TRISC, 13, OUT },
    [EPUCK_PIN_AUDIO_ON] = { DSPIC30_TRISF, 0, OUT },
    // ⚠ Selector pull-ups and polarity are undocumented; read raw as the
    // library does (§3.8).
    [EPUCK_PIN_SELECTOR_0] = { DSPIC30_TRISG, 6, IN },
    [EPUCK_PIN_SELECTOR_1] = { DSPIC30_TRISG, 7, IN },
    [EPUCK_PIN_SELECTOR_2] = { DSPIC30_TRISG, 8, IN },
    [EPUCK_PIN_SELECTOR_3] = { DSPIC30_TRISG, 9, IN },
    [EPUCK_PIN_BATTERY_LOW] = { DSPIC30_TRISF, 1, IN },
    [EPUCK_PIN_REMOTE] = { DSPIC30_TRISF, 6, IN },
    [EPUCK_PIN_CAMERA_HREF] = { DSPIC30_TRISC, 3, IN },
    [EPUCK_PIN_CAMERA_VSYNC] = { DSPIC30_TRISC, 4, IN },
    [EPUCK_PIN_CAMERA_PCLK] = { DSPIC30_TRISC, 14, IN },
};

// The camera's data bus: the upper byte of port D, inputs (§3.5).
#define CAMERA_DATA_BITS 0xFF00u

void dspic30_gpio_init(hal_board *board)
{
    uint16_t i;

    board->edge_callback = 0;
    board->edge_context = 0;
    board->camera_phase = DSPIC30_CAMERA_IDLE;
    board->camera_bytes = 0;
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
