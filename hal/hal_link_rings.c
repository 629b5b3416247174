// The link's rings: see hal_link_rings.h.

#include "hal_link_rings.h"

#define RECEIVE_SLOTS  (HAL_LINK_RECEIVE_CAPACITY + 1u)
#define TRANSMIT_SLOTS (HAL_LINK_TRANSMIT_CAPACITY + 1u)

// The slot after `index` in a ring of `slots`; a compare rather than a mask,
// so that a ring need not be a power of two (the e-puck's is one frame).
static uint16_t next_slot(uint16_t index, uint16_t slots)
{
    index++;
    return index == slots ? 0 : index;
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
    uint16_t next = next_slot(rings->receive_head, RECEIVE_SLOTS);

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
        tail = next_slot(tail, RECEIVE_SLOTS);
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
        head = next_slot(head, TRANSMIT_SLOTS);
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
    rings->transmit_tail = next_slot(tail, TRANSMIT_SLOTS);
    return true;
}

bool hal_link_rings_sending(const hal_link_rings *rings)
{
    return rings->transmit_tail != rings->transmit_head;
}
