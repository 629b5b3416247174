// Stepper phases from a HAL timer: one step per timer period, the period
// being one second divided by the speed.

#include "epuck_motors.h"

#define MICROSECONDS_PER_SECOND 1000000ul
#define PHASE_COUNT             4u
#define PHASE_PINS              4u
#define ALL_PHASE_LINES         0xFu

// The full-step sequence, two coils on at a time (hardware §3.6): bit 3 is
// phase A, bit 0 phase D.
static const uint8_t phase_pattern[PHASE_COUNT] = {
    0x5, // A=0 B=1 C=0 D=1
    0x6, // A=0 B=1 C=1 D=0
    0xA, // A=1 B=0 C=1 D=0
    0x9, // A=1 B=0 C=0 D=1
};

static epuck_pin first_pin(const epuck_motor *motor)
{
    return motor->side == EPUCK_MOTOR_LEFT ? EPUCK_PIN_MOTOR_LEFT_A : EPUCK_PIN_MOTOR_RIGHT_A;
}

static epuck_timer motor_timer(const epuck_motor *motor)
{
    return motor->side == EPUCK_MOTOR_LEFT ? EPUCK_TIMER_MOTOR_LEFT : EPUCK_TIMER_MOTOR_RIGHT;
}

// Drives the four phase lines with `pattern` (bit 3 = A ... bit 0 = D):
// those that change, two a step.
static void write_phases(epuck_motor *motor, uint8_t pattern)
{
    uint8_t i;
    epuck_pin pin = first_pin(motor);
    uint8_t changed = (uint8_t)(motor->lines ^ pattern);

    for (i = 0; i < PHASE_PINS; i++)
        if ((changed >> (PHASE_PINS - 1u - i)) & 1u)
            epuck_board_pin_write(
              motor->board, (epuck_pin)(pin + i), ((pattern >> (PHASE_PINS - 1u - i)) & 1u) != 0);
    motor->lines = pattern;
}

// The timer's callback: one step in the direction of the speed. The motors
// are mirror-mounted, so forward steps the left motor's phase index down and
// the right motor's up (§3.6).
static void step(void *context)
{
    epuck_motor *motor = context;
    bool forward = motor->speed > 0;
    bool index_up = (motor->side == EPUCK_MOTOR_RIGHT) == forward;

    if (motor->speed == 0)
        return;
    motor->phase = (uint8_t)((motor->phase + (index_up ? 1u : PHASE_COUNT - 1u)) % PHASE_COUNT);
    write_phases(motor, phase_pattern[motor->phase]);
    motor->steps = (uint16_t)(motor->steps + (forward ? 1u : 0xFFFFu));
}

void epuck_motor_init(epuck_motor *motor, hal_board *board, epuck_motor_side side)
{
    motor->board = board;
    motor->side = side;
    motor->speed = 0;
    motor->phase = 0;
    motor->steps = 0;
    epuck_board_timer_stop(board, motor_timer(motor));
    // Whatever the lines were driven to before, every one is driven low.
    motor->lines = ALL_PHASE_LINES;
    write_phases(motor, 0);
}

void epuck_motor_set_speed(epuck_motor *motor, int16_t speed)
{
    uint16_t magnitude;

    if (speed > EPUCK_MOTOR_MAX_SPEED)
        speed = EPUCK_MOTOR_MAX_SPEED;
    if (speed < -EPUCK_MOTOR_MAX_SPEED)
        speed = -EPUCK_MOTOR_MAX_SPEED;
    if (speed == motor->speed)
        return;
    if (speed == 0) {
        // Coils left on would overheat the motor (§3.6).
        epuck_board_timer_stop(motor->board, motor_timer(motor));
        motor->speed = 0;
        write_phases(motor, 0);
        return;
    }
    magnitude = (uint16_t)(speed < 0 ? -speed : speed);
    {
        hal_critical_state state = hal_critical_enter(motor->board);
        motor->speed = speed;
        hal_critical_leave(motor->board, state);
    }
    epuck_board_timer_start(
      motor->board, motor_timer(motor), MICROSECONDS_PER_SECOND / magnitude, step, motor);
}

int16_t epuck_motor_speed(const epuck_motor *motor)
{
    return motor->speed;
}

int16_t epuck_motor_steps(epuck_motor *motor)
{
    hal_critical_state state = hal_critical_enter(motor->board);
    uint16_t steps = motor->steps;

    hal_critical_leave(motor->board, state);
    return (int16_t)steps;
}
