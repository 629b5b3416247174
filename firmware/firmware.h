// The firmware: an Aseba node with its robot's description and memory, and
// a main loop over the chip (hal.h) and the robot's devices. Robot-neutral:
// the robot is the package the target's configuration names as
// ROBOT_HEADER (robots/<robot>/), which gives the firmware its variables,
// its description and its devices under the names listed in
// robots/epuck/epuck_robot.h. A chip build owns one instance; the host runs
// as many as it simulates robots.

#ifndef FIRMWARE_H
#define FIRMWARE_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/hal.h"
#include "vm/node.h"

#if !defined(ROBOT_HEADER) || !defined(FIRMWARE_BYTECODE_WORDS) ||                                 \
  !defined(FIRMWARE_STACK_WORDS) || !defined(FIRMWARE_FREE_VARIABLE_WORDS)
#error "the target's configuration must name ROBOT_HEADER and the node's memory sizes (FIRMWARE_*)"
#endif
#include ROBOT_HEADER

// The variables: the robot's named ones, then the words for user variables
// and temporaries.
#define FIRMWARE_VARIABLE_WORDS (ROBOT_NAMED_WORDS + FIRMWARE_FREE_VARIABLE_WORDS)

typedef struct firmware_state {
    hal_board *board;
    robot_devices *robot;
    node_state node;
    uint16_t bytecode[FIRMWARE_BYTECODE_WORDS];
    int16_t stack[FIRMWARE_STACK_WORDS];
    union {
        int16_t words[FIRMWARE_VARIABLE_WORDS];
        robot_variables named;
    } variables;
    // The robot's timer event: the period it runs with (0 = off) and its
    // next due time.
    int16_t timer_period_ms;
    uint32_t next_timer_ms;
    // The millisecond of the last reading of the robot's sensors (its low
    // bits): they are read once a millisecond, not at every pass.
    uint16_t sensed_ms;
} firmware_state;

// Starts the robot's devices on `board` and the node as `node_id`
// (1..0xFFFE), then the stored program if there is one. On the e-puck the
// proximity sensors and the accelerometer calibrate during the first second
// and a half: the robot should stand still (their values are uncalibrated
// until then).
void firmware_init(firmware_state *firmware,
                   hal_board *board,
                   robot_devices *robot,
                   uint16_t node_id);

// One pass of the main loop: link, variables to the robot, its sensors'
// values to the variables and local events (at the first pass of each
// millisecond), VM. Never waits, except when the node sends more than the link's
// transmit buffer holds at once (on the e-puck, any frame over 32 bytes): it
// then waits for the buffer to drain. Returns whether more work is waiting
// (when false the caller may idle until the next input or tick).
bool firmware_poll(firmware_state *firmware);

// Starts `count` words of bytecode as a stored program starts at boot: init
// runs at once, not paused (bytecode.md §6.5).
void firmware_start_program(firmware_state *firmware, const uint16_t *bytecode, uint16_t count);

#endif
