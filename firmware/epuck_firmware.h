// The e-puck firmware: an Aseba node with the e-puck's description, its
// memory, and a main loop over the chip (hal.h) and the robot's board layer
// (epuck_robot.h). A chip build owns one instance; the host runs as many as
// it simulates robots.

#ifndef EPUCK_FIRMWARE_H
#define EPUCK_FIRMWARE_H

#include <stdbool.h>
#include <stdint.h>

#include "epuck_description.h"
#include "epuck_robot.h"
#include "epuck_variables.h"
#include "hal/hal.h"
#include "vm/node.h"

typedef struct epuck_firmware {
    hal_board *board;
    epuck_robot *robot;
    node_state node;
    uint16_t bytecode[EPUCK_BYTECODE_WORDS];
    int16_t stack[EPUCK_STACK_WORDS];
    union {
        int16_t words[EPUCK_VARIABLES_WORDS];
        epuck_named_variables named;
    } variables;
    // The `timer` event: the period it runs with (0 = off) and its next due time.
    int16_t timer_period_ms;
    uint32_t next_timer_ms;
} epuck_firmware;

// Starts the robot's devices on `board` and the node as `node_id`
// (1..0xFFFE), then the stored program if there is one. On the e-puck the
// proximity sensors and the accelerometer calibrate during the first second
// and a half: the robot should stand still (their values are uncalibrated
// until then).
void epuck_firmware_init(epuck_firmware *firmware,
                         hal_board *board,
                         epuck_robot *robot,
                         uint16_t node_id);

// One pass of the main loop: link, variables to the robot and back, local
// events, VM. Never waits, except when the node sends more than the link's
// transmit buffer holds at once (on the e-puck, any frame over 32 bytes): it
// then waits for the buffer to drain. Returns whether more work is waiting
// (when false the caller may idle until the next input or tick).
bool epuck_firmware_poll(epuck_firmware *firmware);

// Starts `count` words of bytecode as a stored program starts at boot: init
// runs at once, not paused (bytecode.md §6.5).
void epuck_firmware_start_program(epuck_firmware *firmware,
                                  const uint16_t *bytecode,
                                  uint16_t count);

// The e-puck's description, as sent to hosts.
extern const node_description epuck_description;

#endif
