// The robot's periodic timers on the chip's 16-bit Timers 2, 3 and 5 (§2.2,
// §3.13): the motors on Timer5 (left) and Timer2 (right), the remote's
// sampling on Timer3. Timer4 counts the camera's rows (dspic30_camera.c):
// the library's motor driver on Timers 4 and 5 and its camera capture on
// the same two cannot run together (§3.13), so the motors moved.

#include "epuck_dspic30_board.h"
#include "ports/dspic30/dspic30_registers.h"

#define MICROSECONDS_PER_SECOND 1000000ul
#define TIMER_REGISTER_MAX      0xFFFFul
#define PRESCALER_COUNT         4u
#define LARGEST_PRESCALE        256u

#define NUMERATOR   DSPIC30_CYCLES_PER_US_NUMERATOR
#define DENOMINATOR DSPIC30_CYCLES_PER_US_DENOMINATOR
typedef char fraction_is_the_clock[(uint64_t)NUMERATOR * MICROSECONDS_PER_SECOND ==
                                       (uint64_t)DSPIC30_FCY_HZ * DENOMINATOR
                                     ? 1
                                     : -1];
typedef char prescales_divide_the_numerator[NUMERATOR % LARGEST_PRESCALE == 0 ? 1 : -1];
// The longest period, in microseconds, each prescaler's 16-bit count holds:
// below it, microseconds × NUMERATOR / prescale fits 32 bits.
#define LONGEST_US(prescale)                                                                       \
    ((uint32_t)((uint64_t)(TIMER_REGISTER_MAX + 1u) * (prescale)*DENOMINATOR / NUMERATOR))
// The longest period the board promises fits the largest prescaler.
typedef char
  longest_period_fits[EPUCK_TIMER_MAX_PERIOD_US <= LONGEST_US(LARGEST_PRESCALE) ? 1 : -1];

// The registers of one chip timer.
typedef struct timer_registers {
    uint16_t control;
    uint16_t period;
    uint16_t count;
    uint16_t flags;  // IFSn
    uint16_t enable; // IECn
    uint16_t bit;
    uint16_t priority; // IPCn
    uint16_t priority_shift;
} timer_registers;

static const timer_registers timer_map[EPUCK_TIMER_COUNT] = {
    [EPUCK_TIMER_MOTOR_LEFT] = { DSPIC30_T5CON,
                                 DSPIC30_PR5,
                                 DSPIC30_TMR5,
                                 DSPIC30_IFS1,
                                 DSPIC30_IEC1,
                                 DSPIC30_IRQ1_T5,
                                 DSPIC30_IPC_T5,
                                 DSPIC30_SHIFT_T5 },
    [EPUCK_TIMER_MOTOR_RIGHT] = { DSPIC30_T2CON,
                                  DSPIC30_PR2,
                                  DSPIC30_TMR2,
                                  DSPIC30_IFS0,
                                  DSPIC30_IEC0,
                                  DSPIC30_IRQ0_T2,
                                  DSPIC30_IPC_T2,
                                  DSPIC30_SHIFT_T2 },
    [EPUCK_TIMER_SPARE] = { DSPIC30_T3CON,
                            DSPIC30_PR3,
                            DSPIC30_TMR3,
                            DSPIC30_IFS0,
                            DSPIC30_IEC0,
                            DSPIC30_IRQ0_T3,
                            DSPIC30_IPC_T3,
                            DSPIC30_SHIFT_T3 },
};

// Prescale of each TCKPS code, and the longest period each allows.
static const uint16_t prescales[PRESCALER_COUNT] = { 1, 8, 64, LARGEST_PRESCALE };
static const uint32_t longest_us[PRESCALER_COUNT] = { LONGEST_US(1),
                                                      LONGEST_US(8),
                                                      LONGEST_US(64),
                                                      LONGEST_US(LARGEST_PRESCALE) };

// One 32-bit division per start: a timer is started from interrupts too
// (the remote's decoding restarts its timer at each step), and the exact
// computation it replaced, several divisions by 10^6 per prescaler, took
// half a millisecond there and made the remote's samples late.
bool dspic30_timer_period(uint32_t period_microseconds,
                          uint16_t *period_register,
                          uint16_t *prescaler_code)
{
    uint16_t code;

    if (period_microseconds < EPUCK_TIMER_MIN_PERIOD_US ||
        period_microseconds > EPUCK_TIMER_MAX_PERIOD_US)
        return false;
    for (code = 0; code < PRESCALER_COUNT; code++) {
        uint32_t counts;
        if (period_microseconds > longest_us[code])
            continue;
        // Timer counts in the period, rounded to the nearest.
        counts =
          (period_microseconds * (NUMERATOR / prescales[code]) + DENOMINATOR / 2u) / DENOMINATOR;
        if (counts >= DSPIC30_TIMER_PERIOD_OFFSET &&
            counts - DSPIC30_TIMER_PERIOD_OFFSET <= TIMER_REGISTER_MAX) {
            *period_register = (uint16_t)(counts - DSPIC30_TIMER_PERIOD_OFFSET);
            *prescaler_code = code;
            return true;
        }
    }
    return false;
}

void dspic30_timers_init(hal_board *board)
{
    uint16_t i;

    for (i = 0; i < EPUCK_TIMER_COUNT; i++) {
        const timer_registers *timer = &timer_map[i];
        board->timers[i].callback = 0;
        board->timers[i].context = 0;
        dspic30_write(timer->control, 0); // off, internal clock, 16-bit
        dspic30_clear_bits(timer->enable, timer->bit);
        dspic30_clear_bits(timer->flags, timer->bit);
        dspic30_set_priority(timer->priority, timer->priority_shift, DSPIC30_PRIORITY_TIMERS);
    }
}

bool epuck_board_timer_start(hal_board *board,
                             epuck_timer timer,
                             uint32_t period_microseconds,
                             epuck_callback callback,
                             void *context)
{
    const timer_registers *registers;
    uint16_t period_register;
    uint16_t prescaler_code;

    if ((uint16_t)timer >= EPUCK_TIMER_COUNT ||
        !dspic30_timer_period(period_microseconds, &period_register, &prescaler_code))
        return false;
    registers = &timer_map[timer];
    epuck_board_timer_stop(board, timer);
    board->timers[timer].callback = callback;
    board->timers[timer].context = context;
    dspic30_write(registers->count, 0);
    dspic30_write(registers->period, period_register);
    dspic30_set_bits(registers->enable, registers->bit);
    dspic30_write(registers->control,
                  (uint16_t)(DSPIC30_TCON_TON | (prescaler_code << DSPIC30_TCON_TCKPS_SHIFT)));
    return true;
}

void epuck_board_timer_stop(hal_board *board, epuck_timer timer)
{
    const timer_registers *registers;

    if ((uint16_t)timer >= EPUCK_TIMER_COUNT)
        return;
    registers = &timer_map[timer];
    dspic30_write(registers->control, 0);
    dspic30_clear_bits(registers->enable, registers->bit);
    dspic30_clear_bits(registers->flags, registers->bit);
    board->timers[timer].callback = 0;
}

void dspic30_on_timer(hal_board *board, epuck_timer timer)
{
    const timer_registers *registers = &timer_map[timer];
    dspic30_timer_slot *slot = &board->timers[timer];

    dspic30_clear_bits(registers->flags, registers->bit);
    if (slot->callback)
        slot->callback(slot->context);
}
