// The link's rings: see hal_link_rings.h.

#include "hal_link_rings.h"

#define RECEIVE_MASK   (HAL_LINK_RECEIVE_CAPACITY - 1u)
#define TRANSMIT_SLOTS (HAL_LINK_TRANSMIT_CAPACITY + 1u)
typedef char
  receive_capacity_is_a_power_of_two[(HAL_LINK_RECEIVE_CAPACITY & RECEIVE_MASK) == 0 ? 1 : -1];

static uint16_t next_transmit_slot(uint16_t index)
{
    index++;
    return index == TRANSMIT_SLOTS ? 0 : index;
}

void hal_link_rings_init(hal_link_rings *rings)
{
    rings->receive_head = 0;
    rings->receive_tail = 0;
    rings->receive_overruns = 0;
    rings->transmit_head = 0;
    rings->transmit_tail = 0;
}

void hal_link_rings_received(hal_link_rings *rings, uint8_t byte)
{
    uint16_t next = (uint16_t)((rings->receive_head + 1u) & RECEIVE_MASK);

    if (next == rings->receive_tail) {
        rings->receive_overruns++;
        return;
    }
    rings->receive[rings->receive_head] = byte;
    rings->receive_head = next;
}

uint16_t hal_link_rings_take(hal_link_rings *rings, uint8_t *bytes, uint16_t capacity)
{
    uint16_t count = 0;
    uint16_t tail = rings->receive_tail;

    while (count < capacity && tail != rings->receive_head) {
        bytes[count++] = rings->receive[tail];
        tail = (uint16_t)((tail + 1u) & RECEIVE_MASK);
    }
    rings->receive_tail = tail;
    return count;
}

uint16_t hal_link_rings_room(const hal_link_rings *rings)
{
    uint16_t head = rings->transmit_head;
    uint16_t tail = rings->transmit_tail;
    uint16_t used =
      head >= tail ? (uint16_t)(head - tail) : (uint16_t)(TRANSMIT_SLOTS - tail + head);

    return (uint16_t)(HAL_LINK_TRANSMIT_CAPACITY - used);
}

uint16_t hal_link_rings_queue(hal_link_rings *rings, const uint8_t *bytes, uint16_t count)
{
    uint16_t room = hal_link_rings_room(rings);
    uint16_t head = rings->transmit_head;
    uint16_t i;

    if (count > room)
        count = room;
    for (i = 0; i < count; i++) {
        rings->transmit[head] = bytes[i];
        head = next_transmit_slot(head);
    }
    rings->transmit_head = head;
    return count;
}

bool hal_link_rings_next_to_send(hal_link_rings *rings, uint8_t *byte)
{
    uint16_t tail = rings->transmit_tail;

    if (tail == rings->transmit_head)
        return false;
    *byte = rings->transmit[tail];
    rings->transmit_tail = next_transmit_slot(tail);
    return true;
}

bool hal_link_rings_sending(const hal_link_rings *rings)
{
    return rings->transmit_tail != rings->transmit_head;
}
