// The hardware abstraction layer: everything the firmware may ask of a board.
//
// Drivers and the firmware are written once against these functions; the
// dsPIC implementation (hal/dspic30) reaches the chip's registers, the host
// implementation (hal/host) simulates a board on a PC. A board is an
// instance: the host holds many, the dsPIC build exactly one.

#ifndef HAL_H
#define HAL_H

#include <stdint.h>

// Defined by each implementation.
typedef struct hal_board hal_board;

// Milliseconds since the board started; wraps after 49 days.
uint32_t hal_milliseconds(hal_board *board);

// Takes up to `capacity` bytes received on the communication link (the
// e-puck's Bluetooth UART) without waiting; returns how many.
uint16_t hal_link_receive(hal_board *board, uint8_t *bytes, uint16_t capacity);

// Sends `count` bytes on the communication link, in order.
void hal_link_send(hal_board *board, const uint8_t *bytes, uint16_t count);

// Sleeps until something may have happened (an interrupt on the chip; the
// host scheduler decides). Returns at once when nothing can wait.
void hal_idle(hal_board *board);

#endif
