// The link's rings (hal/hal_link_rings.c) alone, at the e-puck's capacities:
// what every UART port (ports/dspic30, ports/stm32f4) relies on.
// tests/ports/dspic30 runs them again behind the dsPIC's UART.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

extern "C" {
#include "hal/hal_link_rings.h"
}

namespace
{

std::vector<uint8_t> take(hal_link_rings &rings, uint16_t capacity)
{
    std::vector<uint8_t> bytes(capacity);
    bytes.resize(hal_link_rings_take(&rings, bytes.data(), capacity));
    return bytes;
}

std::vector<uint8_t> drain(hal_link_rings &rings)
{
    std::vector<uint8_t> sent;
    uint8_t byte;
    while (hal_link_rings_next_to_send(&rings, &byte))
        sent.push_back(byte);
    return sent;
}

class LinkRings : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        hal_link_rings_init(rings.get());
    }
    std::unique_ptr<hal_link_rings> rings = std::make_unique<hal_link_rings>();
};

TEST_F(LinkRings, ReceivedBytesComeOutInOrderAcrossTheEnd)
{
    // Twice round the ring, in pieces that cross its end.
    std::vector<uint8_t> out;
    for (uint32_t i = 0; i < 2u * HAL_LINK_RECEIVE_CAPACITY; i++) {
        hal_link_rings_received(rings.get(), uint8_t(i * 7));
        if (i % 100 == 99) {
            auto part = take(*rings, 1000);
            out.insert(out.end(), part.begin(), part.end());
        }
    }
    auto rest = take(*rings, HAL_LINK_RECEIVE_CAPACITY);
    out.insert(out.end(), rest.begin(), rest.end());
    ASSERT_EQ(out.size(), 2u * HAL_LINK_RECEIVE_CAPACITY);
    for (uint32_t i = 0; i < out.size(); i++)
        ASSERT_EQ(out[i], uint8_t(i * 7)) << i;
    EXPECT_EQ(rings->receive_overruns, 0);
}

TEST_F(LinkRings, AFullReceiveRingCountsWhatItDropsAndKeepsWhatItHolds)
{
    for (uint32_t i = 0; i < HAL_LINK_RECEIVE_CAPACITY + 5u; i++)
        hal_link_rings_received(rings.get(), uint8_t(i));
    EXPECT_EQ(rings->receive_overruns, 5);
    auto held = take(*rings, HAL_LINK_RECEIVE_CAPACITY + 5u);
    ASSERT_EQ(held.size(), HAL_LINK_RECEIVE_CAPACITY);
    EXPECT_EQ(held.front(), 0);
    EXPECT_EQ(held.back(), uint8_t(HAL_LINK_RECEIVE_CAPACITY - 1u));
    EXPECT_TRUE(take(*rings, 1).empty());
}

TEST_F(LinkRings, QueueTakesWhatFitsAndTheTransmitterSendsItInOrder)
{
    std::vector<uint8_t> bytes(HAL_LINK_TRANSMIT_CAPACITY + 10u);
    for (size_t i = 0; i < bytes.size(); i++)
        bytes[i] = uint8_t(i + 1);
    EXPECT_EQ(hal_link_rings_room(rings.get()), HAL_LINK_TRANSMIT_CAPACITY);
    EXPECT_FALSE(hal_link_rings_sending(rings.get()));
    EXPECT_EQ(hal_link_rings_queue(rings.get(), bytes.data(), uint16_t(bytes.size())),
              HAL_LINK_TRANSMIT_CAPACITY);
    EXPECT_EQ(hal_link_rings_room(rings.get()), 0);
    EXPECT_TRUE(hal_link_rings_sending(rings.get()));
    auto sent = drain(*rings);
    ASSERT_EQ(sent.size(), HAL_LINK_TRANSMIT_CAPACITY);
    EXPECT_TRUE(std::equal(sent.begin(), sent.end(), bytes.begin()));
    EXPECT_FALSE(hal_link_rings_sending(rings.get()));
    EXPECT_EQ(hal_link_rings_room(rings.get()), HAL_LINK_TRANSMIT_CAPACITY);
}

TEST_F(LinkRings, RoomIsRightWhereverTheTransmitRingStands)
{
    // Every position of the ring's indexes, every fill.
    uint8_t byte = 0;
    for (uint32_t start = 0; start <= HAL_LINK_TRANSMIT_CAPACITY; start++) {
        hal_link_rings_init(rings.get());
        for (uint32_t i = 0; i < start; i++) {
            ASSERT_EQ(hal_link_rings_queue(rings.get(), &byte, 1), 1);
            ASSERT_TRUE(hal_link_rings_next_to_send(rings.get(), &byte));
        }
        for (uint32_t fill = 0; fill <= HAL_LINK_TRANSMIT_CAPACITY; fill++) {
            ASSERT_EQ(hal_link_rings_room(rings.get()), HAL_LINK_TRANSMIT_CAPACITY - fill)
              << start << " " << fill;
            hal_link_rings_queue(rings.get(), &byte, 1);
        }
        EXPECT_EQ(drain(*rings).size(), HAL_LINK_TRANSMIT_CAPACITY);
    }
}

TEST_F(LinkRings, InitEmptiesBothRingsAndTheOverrunCount)
{
    uint8_t byte = 9;
    for (uint32_t i = 0; i < HAL_LINK_RECEIVE_CAPACITY + 1u; i++)
        hal_link_rings_received(rings.get(), byte);
    hal_link_rings_queue(rings.get(), &byte, 1);
    hal_link_rings_init(rings.get());
    EXPECT_EQ(rings->receive_overruns, 0);
    EXPECT_TRUE(take(*rings, 10).empty());
    EXPECT_FALSE(hal_link_rings_sending(rings.get()));
}

} // namespace
