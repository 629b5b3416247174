// The LEDs (hardware §3.7): eight red ones around the ring (0 = front,
// clockwise), the green body LED and the red front LED, all active high.

#ifndef EPUCK_LEDS_H
#define EPUCK_LEDS_H

#include <stdbool.h>
#include <stdint.h>

#include "robots/epuck/epuck_board.h"

#define EPUCK_RING_LED_COUNT 8u

typedef enum epuck_led {
    EPUCK_LED_RING_0 = 0, // ring LEDs are 0..7
    EPUCK_LED_BODY = EPUCK_RING_LED_COUNT,
    EPUCK_LED_FRONT,
    EPUCK_LED_COUNT
} epuck_led;

typedef struct epuck_leds {
    hal_board *board;
    bool on[EPUCK_LED_COUNT];
} epuck_leds;

// Prepares the LEDs, all off.
void epuck_leds_init(epuck_leds *leds, hal_board *board);

// Switches `led` (a ring index 0..7, EPUCK_LED_BODY or EPUCK_LED_FRONT) on or
// off; touches the pin only when the state changes. Ignores other numbers.
void epuck_leds_set(epuck_leds *leds, uint16_t led, bool on);

// Whether `led` is on (false for numbers out of range).
bool epuck_leds_get(const epuck_leds *leds, uint16_t led);

#endif
