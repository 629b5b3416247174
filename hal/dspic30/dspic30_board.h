// The real e-puck board: the state behind hal.h on the dsPIC30F6014A, the
// start-up of each peripheral, and the interrupt handlers as plain functions
// of the board. dspic30_main.c owns the single instance and forwards the
// chip's interrupt vectors to these handlers.

#ifndef DSPIC30_BOARD_H
#define DSPIC30_BOARD_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/hal.h"
#include "dspic30_config.h"

typedef struct dspic30_timer_slot {
    hal_callback callback;
    void *context;
} dspic30_timer_slot;

struct hal_board {
    // The millisecond clock: Timer1 ticks at DSPIC30_CLOCK_TICK_HZ; each tick
    // adds 1000 to `tick_remainder`, and every 1024 of it is one millisecond.
    volatile uint32_t milliseconds;
    uint16_t tick_remainder;

    // Bytes received on UART1, written by the receive interrupt, read by
    // hal_link_receive.
    uint8_t receive[DSPIC30_LINK_RECEIVE_CAPACITY];
    volatile uint16_t receive_head;     // next byte to write (interrupt side)
    volatile uint16_t receive_tail;     // next byte to read (main-loop side)
    volatile uint16_t receive_overruns; // bytes lost to a full ring or FIFO

    dspic30_timer_slot timers[HAL_TIMER_COUNT];

    hal_adc_scan_callback adc_scan_callback;
    void *adc_scan_context;
    uint16_t adc_scan_mask; // 0 = not scanning
    uint8_t adc_scan_count;

    hal_callback remote_edge_callback;
    void *remote_edge_context;
};

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

// Waits until UART1 has sent every byte given to hal_link_send (the
// transmit shift register is empty).
void dspic30_uart_wait_sent(hal_board *board);

// The interrupt handlers; each clears its own flag.
void dspic30_on_clock_tick(hal_board *board);             // Timer1
void dspic30_on_uart1_receive(hal_board *board);          // U1RX
void dspic30_on_timer(hal_board *board, hal_timer timer); // T2..T5
void dspic30_on_adc(hal_board *board);                    // ADC
void dspic30_on_remote_edge(hal_board *board);            // INT0

// Timer `timer`'s period register value and prescaler code (TCKPS) for
// `period_microseconds`; returns false when no prescaler fits.
bool dspic30_timer_period(uint32_t period_microseconds,
                          uint16_t *period_register,
                          uint16_t *prescaler_code);

// ADCS for scans of `channel_count` channels at DSPIC30_ADC_SCAN_RATE_HZ;
// returns false when no valid ADCS gives that rate exactly.
bool dspic30_adc_scan_clock(uint8_t channel_count, uint16_t *adcs);

#endif
