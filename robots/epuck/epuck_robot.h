// The e-puck as the firmware takes a robot (firmware/firmware.h): the
// configuration of every e-puck target names this header as ROBOT_HEADER.
// Under the names every robot package gives the firmware, it holds:
//
//   robot_variables           the named variables as a struct, so that the
//                             firmware and the devices write them by name
//   ROBOT_NAMED_WORDS         their size in words, before the free words
//   ROBOT_LOCAL_EVENT_COUNT   the local events; bit i of robot_sense's
//                             answer is event i (the i-th has id 0xFFFE - i)
//   ROBOT_TIMER_EVENT         the event the firmware raises every
//   robot_timer_period_ms     milliseconds this variable says (0: never)
//   robot_description         the node's description (epuck_robot.c)
//   robot_variables_at_boot   values the variables start with (epuck_robot.c)
//   robot_devices             the devices behind the variables, and
//   robot_start, robot_actuate, robot_sense   what the firmware does with
//                             them, from the device set the target links:
//                             the e-puck's own (devices/epuck_devices.c) or
//                             none, values written by hosts
//                             (boards/netduinoplus2/fed_robot.c)
//
// The port that builds the image owns the devices; the firmware only holds
// a pointer.

#ifndef EPUCK_ROBOT_H
#define EPUCK_ROBOT_H

#include <stdint.h>

#include "epuck_variables.h"
#include "hal/hal.h"
#include "vm/node.h"

typedef epuck_named_variables robot_variables;

#define ROBOT_NAMED_WORDS       EPUCK_NAMED_WORDS
#define ROBOT_LOCAL_EVENT_COUNT EPUCK_LOCAL_EVENT_COUNT
#define ROBOT_TIMER_EVENT       EPUCK_EVENT_timer

// timer.period: the `timer` event's period in milliseconds.
static inline int16_t robot_timer_period_ms(const robot_variables *named)
{
    return named->timer_period[0];
}

// The e-puck's description, as sent to hosts: its name, named variables,
// local events and natives (epuck_natives.h).
extern const node_description robot_description;

// What the variables hold at boot besides zeros: camLine at
// EPUCK_CAM_LINE_AT_BOOT. Called once the node has cleared them.
void robot_variables_at_boot(robot_variables *named);

typedef struct robot_devices robot_devices;

// Starts the devices on `board`, actuators off.
void robot_start(robot_devices *robot, hal_board *board);

// Drives the actuators from the variables (speeds, LEDs), writing back what
// the devices take (speeds clamped to their range).
void robot_actuate(robot_devices *robot, robot_variables *named);

// Writes the sensors' new values into the variables; returns the local
// events to raise, bit i for event EPUCK_EVENT_... i (epuck_variables.h).
uint16_t robot_sense(robot_devices *robot, robot_variables *named);

#endif
