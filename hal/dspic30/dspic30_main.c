// The dsPIC build's entry point: the single static board and firmware, and
// the chip's interrupt vectors, each forwarding to the board's handler.
// (The only mutable file-scope state of the firmware image.)

#include "dspic30_board.h"
#include "dspic30_registers.h"
#include "firmware/epuck_firmware.h"

static hal_board board;
static epuck_firmware firmware;

int main(void)
{
    // Some robots need a second reset after power-on (§1.8, as both Aseba
    // versions do).
    if (dspic30_read(DSPIC30_RCON) & DSPIC30_RCON_POR) {
        dspic30_clear_bits(DSPIC30_RCON, DSPIC30_RCON_POR);
        hal_reset(&board);
    }
    dspic30_board_init(&board);
    // Node id 0: the firmware takes it from the selector.
    epuck_firmware_init(&firmware, &board, 0);
    for (;;) {
        if (!epuck_firmware_poll(&firmware))
            hal_idle(&board);
    }
    return 0;
}

void DSPIC30_INTERRUPT _T1Interrupt(void)
{
    dspic30_on_clock_tick(&board);
}

void DSPIC30_INTERRUPT _U1RXInterrupt(void)
{
    dspic30_on_uart1_receive(&board);
}

void DSPIC30_INTERRUPT _T2Interrupt(void)
{
    dspic30_on_timer(&board, HAL_TIMER_AGENDA);
}

void DSPIC30_INTERRUPT _T3Interrupt(void)
{
    dspic30_on_timer(&board, HAL_TIMER_SPARE);
}

void DSPIC30_INTERRUPT _T4Interrupt(void)
{
    dspic30_on_timer(&board, HAL_TIMER_MOTOR_RIGHT);
}

void DSPIC30_INTERRUPT _T5Interrupt(void)
{
    dspic30_on_timer(&board, HAL_TIMER_MOTOR_LEFT);
}

void DSPIC30_INTERRUPT _ADCInterrupt(void)
{
    dspic30_on_adc(&board);
}

void DSPIC30_INTERRUPT _INT0Interrupt(void)
{
    dspic30_on_remote_edge(&board);
}
