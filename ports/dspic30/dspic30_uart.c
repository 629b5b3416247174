// UART1, the Bluetooth link (§2.1, §3.11): 115200 8N1. Received bytes go by
// interrupt into the board's receive ring; bytes to send wait in the
// transmit ring, which the transmit interrupt moves into the 4-byte buffer
// each time it empties (as the library does), so that sending never waits
// for the line.

#include "dspic30_chip.h"
#include "dspic30_registers.h"

void dspic30_uart_init(hal_board *board)
{
    hal_link_rings_init(&board->link);

    // Off while configuring. 8N1 (PDSEL = 00, STSEL = 0) on the main pins
    // RF2/RF3: ALTIO = 0. ⚠ That the alternate pins are RC13/RC14 (the
    // camera's) comes from family pin names, not the 6014A pin table (§2.1);
    // ALTIO stays 0 either way, since RF3 is the confirmed U1TX.
    dspic30_write(DSPIC30_U1MODE, 0);
    dspic30_write(DSPIC30_U1BRG, DSPIC30_UART_BRG(DSPIC30_LINK_BAUD));
    dspic30_set_priority(DSPIC30_IPC_U1RX, DSPIC30_SHIFT_U1RX, DSPIC30_PRIORITY_UART1);
    dspic30_set_priority(DSPIC30_IPC_U1TX, DSPIC30_SHIFT_U1TX, DSPIC30_PRIORITY_UART1);
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_U1RX | DSPIC30_IRQ0_U1TX);
    dspic30_clear_bits(DSPIC30_IEC0, DSPIC30_IRQ0_U1TX); // enabled while bytes wait
    dspic30_write(DSPIC30_U1MODE, DSPIC30_UMODE_UARTEN);
    // Transmitter on; UTXISEL = 1: a transmit interrupt when the buffer has
    // emptied, refilled 4 bytes at a time (the library's choice, §2.1);
    // URXISEL = 00: a receive interrupt for every byte.
    dspic30_write(DSPIC30_U1STA, DSPIC30_USTA_UTXEN | DSPIC30_USTA_UTXISEL);
    dspic30_set_bits(DSPIC30_IEC0, DSPIC30_IRQ0_U1RX);
}

void dspic30_on_uart1_receive(hal_board *board)
{
    uint16_t status;

    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_U1RX);
    while ((status = dspic30_read(DSPIC30_U1STA)) & DSPIC30_USTA_URXDA)
        hal_link_rings_received(&board->link, (uint8_t)dspic30_read(DSPIC30_U1RXREG));
    // An overrun stops reception until OERR is cleared; the lost bytes make
    // the protocol drop the frame.
    if (status & DSPIC30_USTA_OERR) {
        board->link.receive_overruns++;
        dspic30_clear_bits(DSPIC30_U1STA, DSPIC30_USTA_OERR);
    }
}

uint16_t hal_link_receive(hal_board *board, uint8_t *bytes, uint16_t capacity)
{
    return hal_link_rings_take(&board->link, bytes, capacity);
}

// Moves waiting bytes into the transmit buffer while it has room, and keeps
// the transmit interrupt enabled exactly while bytes wait. Runs with the
// UART's interrupts held off (in the handler, or in a critical section).
static void fill_transmit_buffer(hal_board *board)
{
    uint8_t byte;

    while ((dspic30_read(DSPIC30_U1STA) & DSPIC30_USTA_UTXBF) == 0 &&
           hal_link_rings_next_to_send(&board->link, &byte))
        dspic30_write(DSPIC30_U1TXREG, byte);
    if (hal_link_rings_sending(&board->link))
        dspic30_set_bits(DSPIC30_IEC0, DSPIC30_IRQ0_U1TX);
    else
        dspic30_clear_bits(DSPIC30_IEC0, DSPIC30_IRQ0_U1TX);
}

void dspic30_on_uart1_transmit(hal_board *board)
{
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_U1TX);
    fill_transmit_buffer(board);
}

uint16_t hal_link_send_room(hal_board *board)
{
    return hal_link_rings_room(&board->link);
}

uint16_t hal_link_send(hal_board *board, const uint8_t *bytes, uint16_t count)
{
    hal_critical_state state;

    count = hal_link_rings_queue(&board->link, bytes, count);
    // An idle transmitter raises no interrupt: start it here.
    state = hal_critical_enter(board);
    fill_transmit_buffer(board);
    hal_critical_leave(board, state);
    return count;
}

void dspic30_uart_wait_sent(hal_board *board)
{
    while (hal_link_rings_sending(&board->link))
        ;
    while ((dspic30_read(DSPIC30_U1STA) & DSPIC30_USTA_TRMT) == 0)
        ;
}
