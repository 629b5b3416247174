// The Aseba bootloader image's entry point on the dsPIC30F6014A (linked with
// linker/epuck-bootloader.gld): the chip's reset vector leads here, directly
// or through the factory Tiny Bootloader's trampoline. It starts the clock
// and the link, answers the Aseba bootloader messages (bootloader/
// bootloader.h) as the node id the application will use, and then jumps to
// the application's entry.
//
// Its own interrupts (the millisecond clock, UART1 reception and
// transmission) come through the alternate vector table (INTCON2.ALTIVT =
// 1), which its linker script fills with the handlers below; the primary
// table leads to the application's GOTO table. Before the jump every
// interrupt source is off and the primary table selected, as after a reset,
// so the application's start-up finds the chip as it expects. The only
// mutable file-scope state of the bootloader image.

#include "boards/epuck_dspic30/epuck_dspic30_board.h"
#include "bootloader/bootloader.h"
#include "dspic30_registers.h"
#include "robots/epuck/devices/epuck_selector.h"
#include "store/bytecode_store.h"

static hal_board board;
static bootloader loader;

// Clock, selector pins and UART1, with interrupts masked until the
// alternate table that leads to this image's handlers is selected.
static void start_board(void)
{
    hal_critical_state state = hal_critical_enter(&board);

    dspic30_clock_init(&board);
    dspic30_gpio_init(&board);
    dspic30_uart_init(&board);
    dspic30_set_bits(DSPIC30_INTCON2, DSPIC30_INTCON2_ALTIVT);
    hal_critical_leave(&board, state);
}

// Leaves the chip as a reset does for interrupts (every source disabled,
// no flag pending, the primary table, CPU priority 0), the last byte sent,
// and jumps to `entry`.
static void start_application(uint32_t entry)
{
    hal_critical_state state;

    dspic30_uart_wait_sent(&board); // the BOOTLOADER_ACK of a reset
    state = hal_critical_enter(&board);
    dspic30_write(DSPIC30_T1CON, 0);
    dspic30_write(DSPIC30_IEC0, 0);
    dspic30_write(DSPIC30_IEC1, 0);
    dspic30_write(DSPIC30_IEC2, 0);
    dspic30_write(DSPIC30_IFS0, 0);
    dspic30_write(DSPIC30_IFS1, 0);
    dspic30_write(DSPIC30_IFS2, 0);
    dspic30_clear_bits(DSPIC30_INTCON2, DSPIC30_INTCON2_ALTIVT);
    hal_critical_leave(&board, state);
    // boot_application_valid keeps entries below BOOT_ENTRY_LIMIT (0x10000).
    dspic30_jump((uint16_t)entry);
}

int main(void)
{
    dspic30_reset_again_after_power_on(&board);
    start_board();
    boot_start(
      &loader, &board, store_node_id(&board, epuck_selector_node_id(epuck_selector_read(&board))));
    while (boot_poll(&loader) != BOOT_START_APPLICATION)
        ;
    start_application(loader.application_entry);
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
