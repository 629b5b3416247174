// The dsPIC30F6014A: the state behind hal.h, the start-up of the chip's own
// parts (clock, UART1, flash and EEPROM), and their interrupt handlers as
// plain functions of the board. The state of the peripherals a board drives
// for its robot (Timers 2 to 5, the ADC's scans, INT0's edges, a camera on
// the parallel port) is kept here too, in the chip's terms, so that a board
// (boards/<board>/: boards/epuck_dspic30) needs no state of its own. The
// images' entry points (dspic30_application_main.c,
// dspic30_bootloader_main.c) each own the single instance of their image and
// forward the chip's interrupt vectors to the handlers.

#ifndef DSPIC30_CHIP_H
#define DSPIC30_CHIP_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/hal.h"
#include "hal/hal_link_rings.h"

// A function a peripheral calls back, in interrupt context.
typedef void (*dspic30_callback)(void *context);

// The 16-bit Timers 2 to 5, which a board gives its robot's periodic work.
#define DSPIC30_TIMER_COUNT 4u

typedef struct dspic30_timer_slot {
    dspic30_callback callback;
    void *context;
} dspic30_timer_slot;

// Receives one ADC scan: the values of the scanned channels, lowest first.
typedef void (*dspic30_adc_scan_callback)(void *context, const uint16_t *values, uint8_t count);

// Where a camera row read on the parallel port stands (the board's camera).
typedef enum dspic30_camera_phase {
    DSPIC30_CAMERA_IDLE,
    DSPIC30_CAMERA_WAITING_FOR_FRAME, // for a blank between frames, to count rows from
    DSPIC30_CAMERA_WAITING_FOR_ROW,   // rows counted, for the interrupt that reads the line
    DSPIC30_CAMERA_ROW_READ,
    DSPIC30_CAMERA_ROW_FAILED,
} dspic30_camera_phase;

struct hal_board {
    // The millisecond clock: Timer1 ticks at DSPIC30_CLOCK_TICK_HZ; each tick
    // adds 1000 to `tick_remainder`, and every 1024 of it is one millisecond.
    volatile uint32_t milliseconds;
    uint16_t tick_remainder;

    // UART1's rings: received bytes from its receive interrupt, bytes to
    // send to its transmit interrupt.
    hal_link_rings link;

    // Timers 2 to 5, in the order the board numbers them.
    dspic30_timer_slot timers[DSPIC30_TIMER_COUNT];

    dspic30_adc_scan_callback adc_scan_callback;
    void *adc_scan_context;
    uint16_t adc_scan_mask; // 0 = not scanning
    uint8_t adc_scan_count;

    // INT0's falling edges.
    dspic30_callback edge_callback;
    void *edge_context;

    // The camera row being read; the phase also changes in the interrupt
    // that reads the row.
    volatile dspic30_camera_phase camera_phase;
    uint16_t camera_row;
    uint8_t *camera_bytes;
    uint16_t camera_pixels;
    uint32_t camera_started_ms;
};

// Resets the chip once more when it has just been powered on; the first
// thing each image's entry point does.
void dspic30_reset_again_after_power_on(hal_board *board);

// The chip's own parts: the clock (Timer1, the millisecond count) and
// UART1, the link.
void dspic30_clock_init(hal_board *board);
void dspic30_uart_init(hal_board *board);

// Waits until UART1 has sent every byte given to hal_link_send (the ring
// and the transmit shift register are empty); interrupts must be enabled.
void dspic30_uart_wait_sent(hal_board *board);

// The interrupt handlers of the chip's own parts; each clears its own flag.
void dspic30_on_clock_tick(hal_board *board);     // Timer1
void dspic30_on_uart1_receive(hal_board *board);  // U1RX
void dspic30_on_uart1_transmit(hal_board *board); // U1TX

// The data EEPROM (DSPIC30_EEPROM_WORDS words of 16 bits; nothing in the
// firmware uses it yet): the word at `index` (DSPIC30_EEPROM_ERASED out of
// range); erasing one word; programming one erased word (bits only go from
// 1 to 0). False out of range or on a failure.
uint16_t dspic30_eeprom_read(hal_board *board, uint16_t index);
bool dspic30_eeprom_erase_word(hal_board *board, uint16_t index);
bool dspic30_eeprom_write_word(hal_board *board, uint16_t index, uint16_t value);

#endif
