// The host board's hal.h functions: a clock set by the host and a link made
// of a receive ring and an output callback.

#include "host_board.h"

void host_board_init(hal_board *board,
                     void (*link_output)(void *context, const uint8_t *bytes, uint16_t count),
                     void *link_context)
{
    board->milliseconds = 0;
    board->receive_start = 0;
    board->receive_count = 0;
    board->link_output = link_output;
    board->link_context = link_context;
}

void host_board_set_time(hal_board *board, uint32_t milliseconds)
{
    if ((int32_t)(milliseconds - board->milliseconds) > 0)
        board->milliseconds = milliseconds;
}

uint16_t host_board_link_room(const hal_board *board)
{
    return (uint16_t)(HOST_LINK_RECEIVE_CAPACITY - board->receive_count);
}

bool host_board_link_deliver(hal_board *board, const uint8_t *bytes, uint16_t count)
{
    uint16_t i;

    if (count > host_board_link_room(board))
        return false;
    for (i = 0; i < count; i++) {
        uint16_t at =
          (uint16_t)((board->receive_start + board->receive_count) % HOST_LINK_RECEIVE_CAPACITY);
        board->receive[at] = bytes[i];
        board->receive_count++;
    }
    return true;
}

uint32_t hal_milliseconds(hal_board *board)
{
    return board->milliseconds;
}

uint16_t hal_link_receive(hal_board *board, uint8_t *bytes, uint16_t capacity)
{
    uint16_t count = 0;

    while (count < capacity && board->receive_count != 0) {
        bytes[count++] = board->receive[board->receive_start];
        board->receive_start = (uint16_t)((board->receive_start + 1) % HOST_LINK_RECEIVE_CAPACITY);
        board->receive_count--;
    }
    return count;
}

void hal_link_send(hal_board *board, const uint8_t *bytes, uint16_t count)
{
    if (board->link_output)
        board->link_output(board->link_context, bytes, count);
}

void hal_idle(hal_board *board)
{
    // The host scheduler decides when a board runs again.
    (void)board;
}
