// The robot's board layer under the e-puck firmware: its devices behind the
// firmware's variables. Each board implements these three functions and
// defines struct epuck_robot in its own header: drivers/epuck (the e-puck's
// motors, sensors and camera, on the dsPIC and in the simulator) and
// drivers/fed (a board without devices, whose sensor variables are written
// by hosts: the emulated STM32F4). The port that builds the image owns the
// instance; the firmware only holds a pointer.

#ifndef EPUCK_ROBOT_H
#define EPUCK_ROBOT_H

#include <stdint.h>

#include "epuck_variables.h"
#include "hal/hal.h"

typedef struct epuck_robot epuck_robot;

// Starts the devices on `board`, actuators off.
void epuck_robot_start(epuck_robot *robot, hal_board *board);

// Drives the actuators from the variables (speeds, LEDs), writing back what
// the devices take (speeds clamped to their range).
void epuck_robot_actuate(epuck_robot *robot, epuck_named_variables *named);

// Writes the sensors' new values into the variables; returns the local
// events to raise, bit i for event EPUCK_EVENT_... i (epuck_variables.h).
uint16_t epuck_robot_sense(epuck_robot *robot, epuck_named_variables *named);

#endif
