// UART1, the Bluetooth link (§2.1, §3.11): 115200 8N1. Received bytes go by
// interrupt into the board's receive ring; bytes to send wait in the
// transmit ring, which the transmit interrupt moves into the 4-byte buffer
// each time it empties (as the library does), so that sending never waits
// for the line.

#include "dspic30_board.h"
#include "dspic30_registers.h"

// The receive ring's capacity is a power of two, so indices wrap with a mask.
#define RECEIVE_MASK (HAL_LINK_RECEIVE_CAPACITY - 1u)
typedef char
  receive_capacity_is_a_power_of_two[(HAL_LINK_RECEIVE_CAPACITY & RECEIVE_MASK) == 0 ? 1 : -1];

#define TRANSMIT_SLOTS (HAL_LINK_TRANSMIT_CAPACITY + 1u)

static uint16_t next_transmit_slot(uint16_t index)
{
    index++;
    return index == TRANSMIT_SLOTS ? 0 : index;
}

void dspic30_uart_init(hal_board *board)
{
    board->receive_head = 0;
    board->receive_tail = 0;
    board->receive_overruns = 0;
    board->transmit_head = 0;
    board->transmit_tail = 0;

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

// Moves waiting bytes into the transmit buffer while it has room, and keeps
// the transmit interrupt enabled exactly while bytes wait. Runs with the UART's
// interrupts held off (in the handler, or in a critical section).
static void fill_transmit_buffer(hal_board *board)
{
    uint16_t tail = board->transmit_tail;

    while (tail != board->transmit_head &&
           (dspic30_read(DSPIC30_U1STA) & DSPIC30_USTA_UTXBF) == 0) {
        dspic30_write(DSPIC30_U1TXREG, board->transmit[tail]);
        tail = next_transmit_slot(tail);
    }
    board->transmit_tail = tail;
    if (tail == board->transmit_head)
        dspic30_clear_bits(DSPIC30_IEC0, DSPIC30_IRQ0_U1TX);
    else
        dspic30_set_bits(DSPIC30_IEC0, DSPIC30_IRQ0_U1TX);
}

void dspic30_on_uart1_transmit(hal_board *board)
{
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_U1TX);
    fill_transmit_buffer(board);
}

uint16_t hal_link_send_room(hal_board *board)
{
    uint16_t head = board->transmit_head;
    uint16_t tail = board->transmit_tail;
    uint16_t used =
      head >= tail ? (uint16_t)(head - tail) : (uint16_t)(TRANSMIT_SLOTS - tail + head);

    return (uint16_t)(HAL_LINK_TRANSMIT_CAPACITY - used);
}

uint16_t hal_link_send(hal_board *board, const uint8_t *bytes, uint16_t count)
{
    uint16_t room = hal_link_send_room(board);
    uint16_t head = board->transmit_head;
    uint16_t i;
    hal_critical_state state;

    if (count > room)
        count = room;
    // Only this side moves the head; the interrupt only moves the tail.
    for (i = 0; i < count; i++) {
        board->transmit[head] = bytes[i];
        head = next_transmit_slot(head);
    }
    board->transmit_head = head;
    // An idle transmitter raises no interrupt: start it here.
    state = hal_critical_enter(board);
    fill_transmit_buffer(board);
    hal_critical_leave(board, state);
    return count;
}

void dspic30_uart_wait_sent(hal_board *board)
{
    while (board->transmit_tail != board->transmit_head)
        ;
    while ((dspic30_read(DSPIC30_U1STA) & DSPIC30_USTA_TRMT) == 0)
        ;
}
