// UART1, the Bluetooth link (§2.1, §3.11): 115200 8N1, received bytes go by
// interrupt into the board's ring, sent bytes are written to the transmit
// FIFO as room appears.

#include "dspic30_board.h"
#include "dspic30_registers.h"

// The ring's capacity is a power of two, so indices wrap with a mask.
#define RECEIVE_MASK (DSPIC30_LINK_RECEIVE_CAPACITY - 1u)
typedef char
  receive_capacity_is_a_power_of_two[(DSPIC30_LINK_RECEIVE_CAPACITY & RECEIVE_MASK) == 0 ? 1 : -1];

void dspic30_uart_init(hal_board *board)
{
    board->receive_head = 0;
    board->receive_tail = 0;
    board->receive_overruns = 0;

    // Off while configuring. 8N1 (PDSEL = 00, STSEL = 0) on the main pins
    // RF2/RF3: ALTIO = 0. ⚠ That the alternate pins are RC13/RC14 (the
    // camera's) comes from family pin names, not the 6014A pin table (§2.1);
    // ALTIO stays 0 either way, since RF3 is the confirmed U1TX.
    dspic30_write(DSPIC30_U1MODE, 0);
    dspic30_write(DSPIC30_U1BRG, DSPIC30_UART_BRG(DSPIC30_LINK_BAUD));
    dspic30_set_priority(DSPIC30_IPC_U1RX, DSPIC30_SHIFT_U1RX, DSPIC30_PRIORITY_UART1);
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_U1RX | DSPIC30_IRQ0_U1TX);
    dspic30_clear_bits(DSPIC30_IEC0, DSPIC30_IRQ0_U1TX); // sending polls the FIFO
    dspic30_write(DSPIC30_U1MODE, DSPIC30_UMODE_UARTEN);
    // Transmitter on; URXISEL = 00: an interrupt for every received byte.
    dspic30_write(DSPIC30_U1STA, DSPIC30_USTA_UTXEN);
    dspic30_set_bits(DSPIC30_IEC0, DSPIC30_IRQ0_U1RX);
}

void dspic30_on_uart1_receive(hal_board *board)
{
    uint16_t status;

    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_U1RX);
    while ((status = dspic30_read(DSPIC30_U1STA)) & DSPIC30_USTA_URXDA) {
        uint8_t byte = (uint8_t)dspic30_read(DSPIC30_U1RXREG);
        uint16_t next = (uint16_t)((board->receive_head + 1u) & RECEIVE_MASK);
        if (next == board->receive_tail) {
            board->receive_overruns++;
        } else {
            board->receive[board->receive_head] = byte;
            board->receive_head = next;
        }
    }
    // An overrun stops reception until OERR is cleared; the lost bytes make
    // the protocol drop the frame.
    if (status & DSPIC30_USTA_OERR) {
        board->receive_overruns++;
        dspic30_clear_bits(DSPIC30_U1STA, DSPIC30_USTA_OERR);
    }
}

uint16_t hal_link_receive(hal_board *board, uint8_t *bytes, uint16_t capacity)
{
    uint16_t count = 0;
    uint16_t tail = board->receive_tail;

    // Only this side moves the tail; the interrupt only moves the head.
    while (count < capacity && tail != board->receive_head) {
        bytes[count++] = board->receive[tail];
        tail = (uint16_t)((tail + 1u) & RECEIVE_MASK);
    }
    board->receive_tail = tail;
    return count;
}

void hal_link_send(hal_board *board, const uint8_t *bytes, uint16_t count)
{
    uint16_t i;

    (void)board;
    for (i = 0; i < count; i++) {
        while (dspic30_read(DSPIC30_U1STA) & DSPIC30_USTA_UTXBF)
            ;
        dspic30_write(DSPIC30_U1TXREG, bytes[i]);
    }
}

void dspic30_uart_wait_sent(hal_board *board)
{
    (void)board;
    while ((dspic30_read(DSPIC30_U1STA) & DSPIC30_USTA_TRMT) == 0)
        ;
}
