// The e-puck's devices on QEMU's netduinoplus2, which has none
// (robots/epuck/epuck_robot.h): the sensor variables hold what hosts write
// into them, and the actuator variables go nowhere. The sensor events still
// come at the e-puck's rates, so that a controller runs as on the robot on
// values a test feeds it. A real e-puck2 board would link devices of its
// own instead.

#ifndef FED_ROBOT_H
#define FED_ROBOT_H

#include <stdint.h>

#include "robots/epuck/epuck_robot.h"

// The e-puck raises ir_sensors when a full set of the four IR pairs is in
// (about 63 times a second, robots/epuck/devices/epuck_analog.h) and camera at most
// every 50 ms (robots/epuck/devices/epuck_camera.c), microphones for each
// recording (about every 65 ms, robots/epuck/devices/epuck_microphones.h).
#define FED_ROBOT_PROXIMITY_PERIOD_MS   16u
#define FED_ROBOT_CAMERA_PERIOD_MS      50u
#define FED_ROBOT_MICROPHONES_PERIOD_MS 65u

struct robot_devices {
    hal_board *board;
    uint32_t next_proximity_ms;
    uint32_t next_camera_ms;
    uint32_t next_microphones_ms;
};

#endif
