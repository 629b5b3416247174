// The e-puck on its dsPIC30F6014A: the e-puck's board interface
// (robots/epuck/epuck_board.h) on the chip's peripherals. The pins by name
// (dspic30_pin_map.h, dspic30_gpio.c), the robot's three periodic timers on Timers 2, 3 and 5
// (dspic30_timers.c), the analog inputs and their scans (dspic30_adc.c), the
// I2C bus (dspic30_i2c.c) and the camera's pixel port (dspic30_camera.c),
// with their state in the chip's struct hal_board (ports/dspic30/dspic30_chip.h).

#ifndef EPUCK_DSPIC30_BOARD_H
#define EPUCK_DSPIC30_BOARD_H

#include <stdbool.h>
#include <stdint.h>

#include "ports/dspic30/dspic30_chip.h"
#include "robots/epuck/epuck_board.h"

typedef char robot_timers_fit_the_chip[EPUCK_TIMER_COUNT <= DSPIC30_TIMER_COUNT ? 1 : -1];

// Prepares every peripheral of the e-puck (clock, ports, UART1, timers,
// ADC, I2C, the camera's row counter) and the board's state; interrupts run from then on. Defined
// by the application's entry point: the bootloader image starts only the clock, the pins and the
// UART.
void dspic30_board_init(hal_board *board);

// Each start-up step of the board's peripherals, in the order
// dspic30_board_init calls them (after dspic30_clock_init, then
// dspic30_gpio_init and dspic30_uart_init).
void dspic30_gpio_init(hal_board *board);
void dspic30_timers_init(hal_board *board);
void dspic30_adc_init(hal_board *board);
void dspic30_i2c_init(hal_board *board);
void dspic30_camera_init(hal_board *board);

// The interrupt handlers of the board's peripherals; each clears its own flag.
void dspic30_on_timer(hal_board *board, epuck_timer timer); // T2..T5
void dspic30_on_adc(hal_board *board);                      // ADC
void dspic30_on_remote_edge(hal_board *board);              // INT0
void dspic30_on_camera_row(hal_board *board);               // T4: the row above the line began

// Waits, with the polls given, for HREF to turn active, then reads `pixels`
// pixels of the row at the camera's byte rate, each followed by one it
// skips, into `bytes`; false when HREF did not come. Interrupts must be
// masked: the read is timed by the instructions (dspic30_camera_row.c).
bool dspic30_camera_read_row(uint8_t *bytes, uint16_t pixels, uint16_t polls);

// Timer `timer`'s period register value and prescaler code (TCKPS) for
// `period_microseconds`; returns false when no prescaler fits.
bool dspic30_timer_period(uint32_t period_microseconds,
                          uint16_t *period_register,
                          uint16_t *prescaler_code);

// ADCS for scans of `channel_count` channels at EPUCK_ADC_SCAN_RATE_HZ;
// returns false when no valid ADCS gives that rate exactly.
bool dspic30_adc_scan_clock(uint8_t channel_count, uint16_t *adcs);

#endif
