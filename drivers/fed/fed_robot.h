// A robot board without devices (firmware/epuck_robot.h): its sensor
// variables hold what hosts write into them, and its actuator variables go
// nowhere. The sensor events still come at the e-puck's rates, so that a
// controller runs as on the robot on values a test feeds it. The emulated
// STM32F4 (hal/stm32f4, QEMU's netduinoplus2) uses it; a real e-puck2 board
// will have its own devices folder beside it.

#ifndef FED_ROBOT_H
#define FED_ROBOT_H

#include <stdint.h>

#include "firmware/epuck_robot.h"

// The e-puck raises ir_sensors when a full set of the four IR pairs is in
// (about 63 times a second, drivers/epuck/epuck_analog.h) and camera at most
// every 50 ms (drivers/epuck/epuck_camera.c).
#define FED_ROBOT_PROXIMITY_PERIOD_MS 16u
#define FED_ROBOT_CAMERA_PERIOD_MS    50u

struct epuck_robot {
    hal_board *board;
    uint32_t next_proximity_ms;
    uint32_t next_camera_ms;
};

#endif
