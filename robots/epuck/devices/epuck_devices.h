// The e-puck's own devices behind the firmware's variables
// (robots/epuck/epuck_robot.h): motors, LEDs, the analog sequencer with the
// proximity sensors, accelerometer and microphones, the camera, the remote,
// the selector and the battery line, each an instance of this folder's
// drivers, on the e-puck's board interface (robots/epuck/epuck_board.h).

#ifndef EPUCK_DEVICES_H
#define EPUCK_DEVICES_H

#include "epuck_accelerometer.h"
#include "epuck_analog.h"
#include "epuck_camera.h"
#include "epuck_leds.h"
#include "epuck_microphones.h"
#include "epuck_motors.h"
#include "epuck_proximity.h"
#include "epuck_rc5.h"
#include "robots/epuck/epuck_robot.h"

struct robot_devices {
    hal_board *board;
    // The variables robot_actuate drives, as it last drove them.
    int16_t driven_speeds[2];
    int16_t driven_leds[EPUCK_RING_LED_COUNT];
    epuck_motor left_motor;
    epuck_motor right_motor;
    epuck_leds leds;
    epuck_proximity proximity;
    epuck_accelerometer accelerometer;
    epuck_microphones microphones;
    epuck_analog analog;
    epuck_camera camera;
    epuck_rc5 rc5;
};

#endif
