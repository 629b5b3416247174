// The fed board: events on a clock, variables left to the hosts.

#include "fed_robot.h"

#include <stdbool.h>

void robot_start(robot_devices *robot, hal_board *board)
{
    uint32_t now = hal_milliseconds(board);

    robot->board = board;
    robot->next_proximity_ms = now + FED_ROBOT_PROXIMITY_PERIOD_MS;
    robot->next_camera_ms = now + FED_ROBOT_CAMERA_PERIOD_MS;
    robot->next_microphones_ms = now + FED_ROBOT_MICROPHONES_PERIOD_MS;
}

void robot_actuate(robot_devices *robot, robot_variables *named)
{
    (void)robot;
    (void)named;
}

// Whether `*next` has come; moves it one period on, or a period after `now`
// when the loop fell behind (no burst of catching up).
static bool due(uint32_t *next, uint32_t now, uint32_t period)
{
    if ((int32_t)(now - *next) < 0)
        return false;
    *next += period;
    if ((int32_t)(now - *next) >= 0)
        *next = now + period;
    return true;
}

uint16_t robot_sense(robot_devices *robot, robot_variables *named)
{
    uint32_t now = hal_milliseconds(robot->board);
    uint16_t events = 0;

    (void)named;
    if (due(&robot->next_proximity_ms, now, FED_ROBOT_PROXIMITY_PERIOD_MS))
        events |= 1u << EPUCK_EVENT_ir_sensors;
    if (due(&robot->next_camera_ms, now, FED_ROBOT_CAMERA_PERIOD_MS))
        events |= 1u << EPUCK_EVENT_camera;
    if (due(&robot->next_microphones_ms, now, FED_ROBOT_MICROPHONES_PERIOD_MS))
        events |= 1u << EPUCK_EVENT_microphones;
    return events;
}
