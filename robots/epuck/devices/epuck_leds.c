// LEDs as pins, remembered so that the pins change only when asked to.

#include "epuck_leds.h"

static epuck_pin led_pin(uint16_t led)
{
    if (led == EPUCK_LED_BODY)
        return EPUCK_PIN_BODY_LED;
    if (led == EPUCK_LED_FRONT)
        return EPUCK_PIN_FRONT_LED;
    return (epuck_pin)(EPUCK_PIN_LED_0 + led);
}

void epuck_leds_init(epuck_leds *leds, hal_board *board)
{
    uint16_t led;

    leds->board = board;
    for (led = 0; led < EPUCK_LED_COUNT; led++) {
        leds->on[led] = false;
        epuck_board_pin_write(board, led_pin(led), false);
    }
}

void epuck_leds_set(epuck_leds *leds, uint16_t led, bool on)
{
    if (led >= EPUCK_LED_COUNT || leds->on[led] == on)
        return;
    leds->on[led] = on;
    epuck_board_pin_write(leds->board, led_pin(led), on);
}

bool epuck_leds_get(const epuck_leds *leds, uint16_t led)
{
    return led < EPUCK_LED_COUNT && leds->on[led];
}
