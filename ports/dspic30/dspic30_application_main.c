// The e-puck application image's entry point on the dsPIC30F6014A: the
// single static board, robot devices and firmware, and the interrupt
// handlers, each forwarding to the board's handler (linker/epuck-app.gld
// puts them in the application's GOTO table, where the bootloader image's
// vectors lead). The only mutable file-scope state of the application image.

#include "boards/epuck_dspic30/epuck_dspic30_board.h"
#include "dspic30_registers.h" // DSPIC30_INTERRUPT
#include "firmware/firmware.h"
#include "robots/epuck/devices/epuck_devices.h"
#include "robots/epuck/devices/epuck_selector.h"
#include "store/bytecode_store.h"

static hal_board board;
static robot_devices devices;
static firmware_state firmware;

// Every peripheral of the board, in the order of epuck_dspic30_board.h. Here, not
// beside the clock: the bootloader image starts only the clock, the pins
// and the UART, and must not refer to the rest.
void dspic30_board_init(hal_board *chip_board)
{
    dspic30_clock_init(chip_board);
    dspic30_gpio_init(chip_board);
    dspic30_uart_init(chip_board);
    dspic30_timers_init(chip_board);
    dspic30_adc_init(chip_board);
    dspic30_i2c_init(chip_board);
    dspic30_camera_init(chip_board);
}

int main(void)
{
    dspic30_reset_again_after_power_on(&board);
    dspic30_board_init(&board);
    // The node id the bootloader answered as: the stored settings' or the
    // selector's.
    firmware_init(&firmware,
                  &board,
                  &devices,
                  store_node_id(&board, epuck_selector_node_id(epuck_selector_read(&board))));
    for (;;) {
        if (!firmware_poll(&firmware))
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

void DSPIC30_INTERRUPT _U1TXInterrupt(void)
{
    dspic30_on_uart1_transmit(&board);
}

void DSPIC30_INTERRUPT _T2Interrupt(void)
{
    dspic30_on_timer(&board, EPUCK_TIMER_MOTOR_RIGHT);
}

void DSPIC30_INTERRUPT _T3Interrupt(void)
{
    dspic30_on_timer(&board, EPUCK_TIMER_SPARE);
}

void DSPIC30_INTERRUPT _T4Interrupt(void)
{
    dspic30_on_camera_row(&board);
}

void DSPIC30_INTERRUPT _T5Interrupt(void)
{
    dspic30_on_timer(&board, EPUCK_TIMER_MOTOR_LEFT);
}

void DSPIC30_INTERRUPT _ADCInterrupt(void)
{
    dspic30_on_adc(&board);
}

void DSPIC30_INTERRUPT _INT0Interrupt(void)
{
    dspic30_on_remote_edge(&board);
}
