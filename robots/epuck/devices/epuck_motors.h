// The two stepper motors (hardware §3.6): each driven by its own HAL timer,
// stepping through the four-phase full-step sequence at a commanded speed in
// steps per second, and counting the steps it makes.

#ifndef EPUCK_MOTORS_H
#define EPUCK_MOTORS_H

#include <stdbool.h>
#include <stdint.h>

#include "robots/epuck/epuck_board.h"

// The speed range of the library's API (§3.6): one wheel turn a second.
#define EPUCK_MOTOR_MAX_SPEED 1000

typedef enum epuck_motor_side { EPUCK_MOTOR_LEFT, EPUCK_MOTOR_RIGHT } epuck_motor_side;

typedef struct epuck_motor {
    hal_board *board;
    epuck_motor_side side;
    int16_t speed;  // steps/s, within ±EPUCK_MOTOR_MAX_SPEED
    uint8_t phase;  // index into the full-step sequence, 0..3
    uint8_t lines;  // the phase lines as last driven (bit 3 = A ... bit 0 = D)
    uint16_t steps; // steps made, forward counting up (wraps)
} epuck_motor;

// Prepares the motor on `side` stopped, its coils off, its step count 0.
void epuck_motor_init(epuck_motor *motor, hal_board *board, epuck_motor_side side);

// Runs the motor at `speed` steps/s (positive = forward), clamped to
// ±EPUCK_MOTOR_MAX_SPEED; 0 stops it and switches its coils off. Does
// nothing when the speed is unchanged, so it may be called every loop.
void epuck_motor_set_speed(epuck_motor *motor, int16_t speed);

// The speed the motor runs at, after clamping.
int16_t epuck_motor_speed(const epuck_motor *motor);

// Steps made since init, +1 per forward step, −1 per backward step,
// wrapping as a 16-bit two's-complement counter.
int16_t epuck_motor_steps(epuck_motor *motor);

#endif
