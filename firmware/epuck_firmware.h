// The e-puck firmware: an Aseba node with the e-puck's description, its
// memory, and a main loop over the board (hal.h). The dsPIC build owns one
// instance; the host runs as many as it simulates robots.

#ifndef EPUCK_FIRMWARE_H
#define EPUCK_FIRMWARE_H

#include <stdbool.h>
#include <stdint.h>

#include "epuck_config.h"
#include "drivers/epuck/epuck_accelerometer.h"
#include "drivers/epuck/epuck_analog.h"
#include "drivers/epuck/epuck_camera.h"
#include "drivers/epuck/epuck_leds.h"
#include "drivers/epuck/epuck_microphones.h"
#include "drivers/epuck/epuck_motors.h"
#include "drivers/epuck/epuck_proximity.h"
#include "drivers/epuck/epuck_rc5.h"
#include "epuck_description.h"
#include "hal/hal.h"
#include "vm/node.h"

// The VM's variables: the named ones as a struct, so the firmware reads and
// writes them by name, then the words left for user variables.
typedef struct epuck_named_variables {
#define EPUCK_VARIABLE_MEMBER(identifier, name, size) int16_t identifier[size];
    EPUCK_VARIABLE_LIST(EPUCK_VARIABLE_MEMBER)
#undef EPUCK_VARIABLE_MEMBER
} epuck_named_variables;

#define EPUCK_VARIABLE_WORDS(identifier, name, size) +(size)
#define EPUCK_NAMED_WORDS                            (0 EPUCK_VARIABLE_LIST(EPUCK_VARIABLE_WORDS))
#define EPUCK_VARIABLES_WORDS                        (EPUCK_NAMED_WORDS + EPUCK_FREE_WORDS)

// The struct must lay the variables out exactly as the description counts them.
typedef char epuck_named_variables_have_no_padding
  [sizeof(epuck_named_variables) == EPUCK_NAMED_WORDS * sizeof(int16_t) ? 1 : -1];

typedef struct epuck_firmware {
    hal_board *board;
    node_state node;
    uint16_t bytecode[EPUCK_BYTECODE_WORDS];
    int16_t stack[EPUCK_STACK_WORDS];
    union {
        int16_t words[EPUCK_VARIABLES_WORDS];
        epuck_named_variables named;
    } variables;
    // Received bytes the node could not take yet (a frame was waiting).
    uint8_t link_bytes[EPUCK_LINK_CHUNK];
    uint16_t link_start;
    uint16_t link_count;
    // The board's devices.
    epuck_motor left_motor;
    epuck_motor right_motor;
    epuck_leds leds;
    epuck_proximity proximity;
    epuck_accelerometer accelerometer;
    epuck_microphones microphones;
    epuck_analog analog;
    epuck_camera camera;
    epuck_rc5 rc5;
    // The `timer` event: the period it runs with (0 = off) and its next due time.
    int16_t timer_period_ms;
    uint32_t next_timer_ms;
} epuck_firmware;

// Starts the drivers on `board` and the node as `node_id` (1..0xFFFE), or,
// when `node_id` is 0, as the bootloader does (epuck_store_node_id: the
// stored settings' id, else (selector & 7) + 1). The proximity sensors and the
// accelerometer calibrate during the first second and a half: the robot
// should stand still (their values are uncalibrated until then).
void epuck_firmware_init(epuck_firmware *firmware, hal_board *board, uint16_t node_id);

// One pass of the main loop: link, drivers to variables and back, local
// events, VM; never blocks, but for reading a camera line on the robot.
// Returns whether more work is waiting (when false the caller may idle
// until the next input or tick).
bool epuck_firmware_poll(epuck_firmware *firmware);

// Starts `count` words of bytecode as a stored program starts at boot: init
// runs at once, not paused (bytecode.md §6.5).
void epuck_firmware_start_program(epuck_firmware *firmware,
                                  const uint16_t *bytecode,
                                  uint16_t count);

// The e-puck's description, as sent to hosts.
extern const node_description epuck_description;

#endif
