// The real e-puck board: the state behind hal.h and the e-puck's board
// (drivers/epuck/epuck_board.h) on the dsPIC30F6014A, the start-up of each
// peripheral, and the interrupt handlers as plain functions of the board.
// The two entry points (dspic30_application_main.c,
// dspic30_bootloader_main.c) each own the single instance of their image
// and forward the chip's interrupt vectors to these handlers.

#ifndef DSPIC30_BOARD_H
#define DSPIC30_BOARD_H

#include <stdbool.h>
#include <stdint.h>

#include "drivers/epuck/epuck_board.h"
#include "dspic30_config.h"
#include "hal/hal.h"
#include "hal/hal_link_rings.h"

typedef struct dspic30_timer_slot {
    epuck_callback callback;
    void *context;
} dspic30_timer_slot;

// Where a camera row read stands (dspic30_camera.c).
typedef enum dspic30_camera_phase {
    DSPIC30_CAMERA_IDLE,
    DSPIC30_CAMERA_WAITING_FOR_FRAME,
} dspic30_camera_phase;

struct hal_board {
    // The millisecond clock: Timer1 ticks at DSPIC30_CLOCK_TICK_HZ; each tick
    // adds 1000 to `tick_remainder`, and every 1024 of it is one millisecond.
    volatile uint32_t milliseconds;
    uint16_t tick_remainder;

    // UART1's rings: received bytes from its receive interrupt, bytes to
    // send to its transmit interrupt.
    hal_link_rings link;

    dspic30_timer_slot timers[EPUCK_TIMER_COUNT];

    epuck_adc_scan_callback adc_scan_callback;
    void *adc_scan_context;
    uint16_t adc_scan_mask; // 0 = not scanning
    uint8_t adc_scan_count;

    epuck_callback remote_edge_callback;
    void *remote_edge_context;

    // The camera row being read (epuck_board_camera_start).
    dspic30_camera_phase camera_phase;
    uint16_t camera_row;
    uint8_t *camera_bytes;
    uint16_t camera_pixels;
    uint32_t camera_started_ms;
};

// Resets the chip once more when it has just been powered on; the first
// thing each image's entry point does.
void dspic30_reset_again_after_power_on(hal_board *board);

// Prepares every peripheral of the e-puck (clock, ports, UART1, timers,
// ADC, I2C) and the board's state; interrupts run from then on.
void dspic30_board_init(hal_board *board);

// Each start-up step, in the order dspic30_board_init calls them.
void dspic30_clock_init(hal_board *board);
void dspic30_gpio_init(hal_board *board);
void dspic30_uart_init(hal_board *board);
void dspic30_timers_init(hal_board *board);
void dspic30_adc_init(hal_board *board);
void dspic30_i2c_init(hal_board *board);

// Waits until UART1 has sent every byte given to hal_link_send (the ring
// and the transmit shift register are empty); interrupts must be enabled.
void dspic30_uart_wait_sent(hal_board *board);

// The interrupt handlers; each clears its own flag.
void dspic30_on_clock_tick(hal_board *board);               // Timer1
void dspic30_on_uart1_receive(hal_board *board);            // U1RX
void dspic30_on_uart1_transmit(hal_board *board);           // U1TX
void dspic30_on_timer(hal_board *board, epuck_timer timer); // T2..T5
void dspic30_on_adc(hal_board *board);                      // ADC
void dspic30_on_remote_edge(hal_board *board);              // INT0

// The data EEPROM (DSPIC30_EEPROM_WORDS words of 16 bits; nothing in the
// firmware uses it yet): the word at `index` (DSPIC30_EEPROM_ERASED out of
// range); erasing one word; programming one erased word (bits only go from
// 1 to 0). False out of range or on a failure.
uint16_t dspic30_eeprom_read(hal_board *board, uint16_t index);
bool dspic30_eeprom_erase_word(hal_board *board, uint16_t index);
bool dspic30_eeprom_write_word(hal_board *board, uint16_t index, uint16_t value);

// Timer `timer`'s period register value and prescaler code (TCKPS) for
// `period_microseconds`; returns false when no prescaler fits.
bool dspic30_timer_period(uint32_t period_microseconds,
                          uint16_t *period_register,
                          uint16_t *prescaler_code);

// ADCS for scans of `channel_count` channels at EPUCK_ADC_SCAN_RATE_HZ;
// returns false when no valid ADCS gives that rate exactly.
bool dspic30_adc_scan_clock(uint8_t channel_count, uint16_t *adcs);

#endif
