// The e-puck's devices behind the firmware's variables, in the upstream
// firmware's order (hardware §6.1): speeds and LEDs out, sensors in.

#include "epuck_devices.h"

#include "epuck_battery.h"
#include "epuck_selector.h"

// The firmware's recording variables hold one recording each.
typedef char
  recordings_fit_the_variables[EPUCK_MIC_RECORD_WORDS == EPUCK_MICROPHONE_RECORD_SAMPLES ? 1 : -1];

void robot_start(robot_devices *robot, hal_board *board)
{
    uint16_t led;

    // The actuators start off, as zeros in the variables ask.
    robot->board = board;
    robot->driven_speeds[0] = robot->driven_speeds[1] = 0;
    for (led = 0; led < EPUCK_RING_LED_COUNT; led++)
        robot->driven_leds[led] = 0;
    epuck_motor_init(&robot->left_motor, board, EPUCK_MOTOR_LEFT);
    epuck_motor_init(&robot->right_motor, board, EPUCK_MOTOR_RIGHT);
    epuck_leds_init(&robot->leds, board);
    epuck_proximity_init(&robot->proximity, board);
    epuck_accelerometer_init(&robot->accelerometer, board);
    epuck_microphones_init(&robot->microphones, board);
    // The analog scan's first second and a half calibrates the proximity
    // sensors and the accelerometer (hardware §6.6).
    epuck_analog_start(
      &robot->analog, board, &robot->proximity, &robot->accelerometer, &robot->microphones);
    epuck_camera_init(&robot->camera, board);
    epuck_rc5_init(&robot->rc5, board);
}

// What a device already holds costs a comparison, no call.
static void drive_motor(epuck_motor *motor, int16_t *speed)
{
    if (*speed == motor->speed)
        return;
    epuck_motor_set_speed(motor, *speed);
    *speed = epuck_motor_speed(motor);
}

// The main loop actuates on every pass, many times between two changes of
// the variables: a pass that finds them as last driven costs one look at
// ten words (without a branch for each, so that a compiler can take the
// eight LEDs together).
void robot_actuate(robot_devices *robot, robot_variables *named)
{
    uint16_t changed = (uint16_t)((named->left_speed[0] ^ robot->driven_speeds[0]) |
                                  (named->right_speed[0] ^ robot->driven_speeds[1]));
    uint16_t led;

    for (led = 0; led < EPUCK_RING_LED_COUNT; led++)
        changed |= (uint16_t)(named->leds[led] ^ robot->driven_leds[led]);
    if (changed == 0)
        return;
    drive_motor(&robot->left_motor, named->left_speed);
    drive_motor(&robot->right_motor, named->right_speed);
    for (led = 0; led < EPUCK_RING_LED_COUNT; led++) {
        bool on = named->leds[led] != 0;

        if (robot->leds.on[led] != on)
            epuck_leds_set(&robot->leds, led, on);
    }
    robot->driven_speeds[0] = named->left_speed[0];
    robot->driven_speeds[1] = named->right_speed[0];
    for (led = 0; led < EPUCK_RING_LED_COUNT; led++)
        robot->driven_leds[led] = named->leds[led];
}

uint16_t robot_sense(robot_devices *robot, robot_variables *named)
{
    uint16_t events = 0;
    uint8_t toggle;
    uint8_t address;
    uint8_t command;
    int16_t *const recordings[EPUCK_MICROPHONE_COUNT] = { named->mic_samples0,
                                                          named->mic_samples1,
                                                          named->mic_samples2 };

    if (epuck_proximity_take(&robot->proximity, named->prox, named->ambient))
        events |= 1u << EPUCK_EVENT_ir_sensors;
    epuck_accelerometer_read(&robot->accelerometer, named->acc);
    epuck_microphones_read(&robot->microphones, named->mic);
    if (epuck_microphones_take_recording(&robot->microphones, recordings))
        events |= 1u << EPUCK_EVENT_microphones;
    if (epuck_camera_capture(
          &robot->camera, named->cam_line[0], named->cam_red, named->cam_green, named->cam_blue))
        events |= 1u << EPUCK_EVENT_camera;
    named->steps_left[0] = epuck_motor_steps(&robot->left_motor);
    named->steps_right[0] = epuck_motor_steps(&robot->right_motor);
    named->battery[0] = epuck_battery_ok(robot->board) ? 1 : 0;
    named->selector[0] = (int16_t)epuck_selector_read(robot->board);
    if (epuck_rc5_take(&robot->rc5, &toggle, &address, &command))
        named->rc5[0] = command;
    return events;
}
