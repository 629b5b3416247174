// The network's robot radio switch (host::Network::relay_robot_events): a
// user event a board sends reaches the other boards only while the radio is
// on; protocol messages always do. Frames are built by hand from
// protocol.md §2 (length of the payload, source, type, payload, little
// endian) and put on a board's link as its firmware would send them.

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "tools/emulator/network.hpp"

namespace
{

// A user event (types below 0x8000): event 0 from node 1 with one argument.
const std::vector<uint8_t> user_event = { 2, 0, 1, 0, 0, 0, 42, 0 };
// A protocol message (0x900C, "node present", protocol.md) from node 1.
const std::vector<uint8_t> node_present = { 2, 0, 1, 0, 0x0C, 0x90, 5, 0 };

struct NetworkRelay : testing::Test {
    std::unique_ptr<hal_board> sender = std::make_unique<hal_board>();
    std::unique_ptr<hal_board> receiver = std::make_unique<hal_board>();
    aseba::host::Network network;

    void SetUp() override
    {
        host_board_init(sender.get(), nullptr, nullptr);
        host_board_init(receiver.get(), nullptr, nullptr);
        network.attach(sender.get());
        network.attach(receiver.get());
    }

    // Sends `frame` from the sender's link and lets the network move it;
    // returns the bytes that reached the receiver's link.
    std::vector<uint8_t> send(const std::vector<uint8_t> &frame)
    {
        sender->link_output(sender->link_context, frame.data(), uint16_t(frame.size()));
        network.service(0);
        std::vector<uint8_t> received;
        for (uint16_t i = 0; i < receiver->receive_count; i++)
            received.push_back(
              receiver->receive[(receiver->receive_start + i) % HAL_LINK_RECEIVE_CAPACITY]);
        return received;
    }
};

} // namespace

TEST_F(NetworkRelay, RobotEventsReachOtherBoardsByDefault)
{
    EXPECT_EQ(send(user_event), user_event);
    EXPECT_EQ(sender->receive_count, 0) << "a board does not hear itself";
}

TEST_F(NetworkRelay, RadioOffKeepsRobotEventsFromOtherBoards)
{
    network.relay_robot_events(false);
    EXPECT_TRUE(send(user_event).empty());
    // Still on the bus for tools.
    EXPECT_EQ(network.frames_moved(), 1u);
}

TEST_F(NetworkRelay, RadioOffStillPassesProtocolMessages)
{
    network.relay_robot_events(false);
    EXPECT_EQ(send(node_present), node_present);
}

TEST_F(NetworkRelay, RadioBackOnRelaysAgain)
{
    network.relay_robot_events(false);
    send(user_event);
    network.relay_robot_events(true);
    EXPECT_EQ(send(user_event), user_event);
}
