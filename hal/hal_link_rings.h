// The two rings of a chip's link, for the ports' UART code: received bytes
// go in from the receive interrupt and out to hal_link_receive; bytes to
// send go in from hal_link_send and out to the transmitter, from its
// interrupt or a polling loop. Each side moves only its own index, so
// neither needs a critical section where a 16-bit store is atomic. The
// capacities are the target's (HAL_LINK_RECEIVE_CAPACITY and
// HAL_LINK_TRANSMIT_CAPACITY, any sizes).

#ifndef HAL_LINK_RINGS_H
#define HAL_LINK_RINGS_H

#include <stdbool.h>
#include <stdint.h>

#include "hal.h"

typedef struct hal_link_rings {
    // Each ring keeps one slot free, so that head == tail means empty.
    uint8_t receive[HAL_LINK_RECEIVE_CAPACITY + 1u];
    volatile uint16_t receive_head;     // next byte to write (interrupt side)
    volatile uint16_t receive_tail;     // next byte to read (main-loop side)
    volatile uint16_t receive_overruns; // bytes lost to a full ring or the UART
    uint8_t transmit[HAL_LINK_TRANSMIT_CAPACITY + 1u];
    volatile uint16_t transmit_head; // next byte to write (main-loop side)
    volatile uint16_t transmit_tail; // next byte to send (transmitter side)
} hal_link_rings;

// Empties both rings and zeroes the overrun count.
void hal_link_rings_init(hal_link_rings *rings);

// Interrupt side: keeps a received byte, or counts it lost when the ring is full.
void hal_link_rings_received(hal_link_rings *rings, uint8_t byte);

// Main-loop side: takes up to `capacity` received bytes; returns how many.
uint16_t hal_link_rings_take(hal_link_rings *rings, uint8_t *bytes, uint16_t capacity);

// Main-loop side: queues up to `count` bytes to send; returns how many fit.
uint16_t hal_link_rings_queue(hal_link_rings *rings, const uint8_t *bytes, uint16_t count);

// How many more bytes hal_link_rings_queue would take now.
uint16_t hal_link_rings_room(const hal_link_rings *rings);

// Transmitter side: takes the next byte to send; false when none waits.
bool hal_link_rings_next_to_send(hal_link_rings *rings, uint8_t *byte);

// Whether bytes wait to be sent.
bool hal_link_rings_sending(const hal_link_rings *rings);

#endif
