// The board's clock: its millisecond clock (Timer1), interrupt masking,
// reset and idle on the dsPIC30F6014A.
//
// The oscillator itself is set by the FOSC configuration word (XT crystal
// with PLL x8, §1.5), emitted here; at run time the code only waits for the
// PLL to lock.

#include "dspic30_chip.h"
#include "dspic30_registers.h"

// The configuration words of §1.5, placed at 0xF80000.. by the linker script.
DSPIC30_CONFIG_WORD(FOSC, DSPIC30_FOSC_VALUE);
DSPIC30_CONFIG_WORD(FWDT, DSPIC30_FWDT_VALUE);
DSPIC30_CONFIG_WORD(FBORPOR, DSPIC30_FBORPOR_VALUE);
DSPIC30_CONFIG_WORD(FGS, DSPIC30_FGS_VALUE);

#define MICROSECONDS_PER_SECOND 1000000ul
#define MILLISECONDS_PER_SECOND 1000u

void dspic30_clock_init(hal_board *board)
{
    uint16_t attempts;

    board->milliseconds = 0;
    board->tick_remainder = 0;

    // The primary oscillator with its PLL comes from FOSC; wait for the lock.
    for (attempts = 0; attempts < DSPIC30_PLL_LOCK_ATTEMPTS; attempts++) {
        if (dspic30_read(DSPIC30_OSCCON) & DSPIC30_OSCCON_LOCK)
            break;
    }

    // Nested interrupts allowed (as the library does), primary vector table.
    dspic30_clear_bits(DSPIC30_INTCON1, DSPIC30_INTCON1_NSTDIS);
    dspic30_clear_bits(DSPIC30_INTCON2, DSPIC30_INTCON2_ALTIVT);

    // Timer1 at 1:1 interrupts DSPIC30_CLOCK_TICK_HZ times a second.
    dspic30_write(DSPIC30_T1CON, 0);
    dspic30_write(DSPIC30_TMR1, 0);
    dspic30_write(DSPIC30_PR1,
                  (uint16_t)(DSPIC30_FCY_HZ / DSPIC30_CLOCK_TICK_HZ - DSPIC30_TIMER_PERIOD_OFFSET));
    dspic30_set_priority(DSPIC30_IPC_T1, DSPIC30_SHIFT_T1, DSPIC30_PRIORITY_CLOCK);
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_T1);
    dspic30_set_bits(DSPIC30_IEC0, DSPIC30_IRQ0_T1);
    dspic30_write(DSPIC30_T1CON, DSPIC30_TCON_TON);
}

void dspic30_on_clock_tick(hal_board *board)
{
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_T1);
    board->tick_remainder = (uint16_t)(board->tick_remainder + MILLISECONDS_PER_SECOND);
    while (board->tick_remainder >= DSPIC30_CLOCK_TICK_HZ) {
        board->tick_remainder = (uint16_t)(board->tick_remainder - DSPIC30_CLOCK_TICK_HZ);
        board->milliseconds++;
    }
}

uint32_t hal_milliseconds(hal_board *board)
{
    // A 32-bit read takes two instructions: read again if a tick came between.
    uint32_t first;
    uint32_t second;

    do {
        first = board->milliseconds;
        second = board->milliseconds;
    } while (first != second);
    return first;
}

void hal_delay_microseconds(hal_board *board, uint16_t microseconds)
{
    uint32_t iterations = (uint32_t)microseconds * (DSPIC30_FCY_HZ / MICROSECONDS_PER_SECOND) /
                          DSPIC30_DELAY_CYCLES_PER_ITERATION;
    (void)board;
    while (iterations-- > 0)
        dspic30_nop();
}

hal_critical_state hal_critical_enter(hal_board *board)
{
    uint16_t status = dspic30_read(DSPIC30_SR);
    (void)board;
    dspic30_write(DSPIC30_SR, (uint16_t)(status | (DSPIC30_PRIORITY_ALL << DSPIC30_SR_IPL_SHIFT)));
    return (hal_critical_state)(status & DSPIC30_SR_IPL_MASK);
}

void hal_critical_leave(hal_board *board, hal_critical_state state)
{
    uint16_t status = dspic30_read(DSPIC30_SR);
    (void)board;
    dspic30_write(
      DSPIC30_SR,
      (uint16_t)((status & (uint16_t)~DSPIC30_SR_IPL_MASK) | (state & DSPIC30_SR_IPL_MASK)));
}

void dspic30_reset_again_after_power_on(hal_board *board)
{
    // Some robots need a second reset after power-on (§1.8, as both Aseba
    // versions do).
    if (dspic30_read(DSPIC30_RCON) & DSPIC30_RCON_POR) {
        dspic30_clear_bits(DSPIC30_RCON, DSPIC30_RCON_POR);
        hal_reset(board);
    }
}

void hal_reset(hal_board *board)
{
    (void)board;
    dspic30_reset_instruction();
}

void hal_idle(hal_board *board)
{
    // Idle mode: the CPU stops until the next interrupt (at least the clock's).
    (void)board;
    dspic30_idle_instruction();
}
