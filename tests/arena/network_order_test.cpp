// Every frame crosses host::Network once and in the order it was sent,
// however the network batches them: a tool sends numbered events as fast as
// its socket takes them, a robot answers each with an event of the same
// number, and the test checks the exact sequences that every member hears.
// On bare host boards whose links the test reads as firmware would.

#include <memory>
#include <vector>

#include "network_test_support.hpp"
#include "tools/emulator/network.hpp"

namespace
{

using namespace network_test;
using namespace aseba::host;

constexpr uint16_t ping_type = 0;      // a user event from the tool
constexpr uint16_t pong_type = 1;      // the robot's answer
constexpr uint16_t robot_1_source = 1; // node id of the answering robot
constexpr uint16_t event_count = 20000;
constexpr size_t frame_bytes = 8; // header and one argument word
constexpr int service_wait_ms = 1;
constexpr int enough_rounds = 200000; // a loopback is fast: a bound, not a pace

Bytes event(uint16_t source, uint16_t type, uint16_t number)
{
    return { 2,
             0,
             uint8_t(source & 0xFF),
             uint8_t(source >> 8),
             uint8_t(type & 0xFF),
             uint8_t(type >> 8),
             uint8_t(number & 0xFF),
             uint8_t(number >> 8) };
}

// The numbers of the events of `type` in `stream`, in order; a frame of any
// other shape fails the test.
std::vector<uint16_t> numbers_of(const Bytes &stream, uint16_t type)
{
    std::vector<uint16_t> numbers;
    EXPECT_EQ(stream.size() % frame_bytes, 0u) << "a frame cut or of another length";
    for (size_t at = 0; at + frame_bytes <= stream.size(); at += frame_bytes) {
        EXPECT_EQ(stream[at], 2) << "at byte " << at;
        if (uint16_t(stream[at + 4] | (stream[at + 5] << 8)) == type)
            numbers.push_back(uint16_t(stream[at + 6] | (stream[at + 7] << 8)));
    }
    return numbers;
}

std::vector<uint16_t> zero_to(uint16_t count)
{
    std::vector<uint16_t> numbers(count);
    for (uint16_t i = 0; i < count; i++)
        numbers[i] = i;
    return numbers;
}

} // namespace

TEST(NetworkOrder, EveryEventArrivesOnceAndInOrder)
{
    auto robot_1 = std::make_unique<hal_board>();
    auto robot_2 = std::make_unique<hal_board>();
    host_board_init(robot_1.get(), nullptr, nullptr);
    host_board_init(robot_2.get(), nullptr, nullptr);
    Network network;
    network.attach(robot_1.get());
    network.attach(robot_2.get());
    uint16_t port = network.listen(0);
    ToolSocket tool(port);
    ToolSocket listener(port);
    for (int round = 0; round < enough_rounds && network.client_count() < 2; round++)
        network.service(service_wait_ms);
    ASSERT_EQ(network.client_count(), 2u);

    Bytes pings;
    for (uint16_t i = 0; i < event_count; i++) {
        Bytes ping = event(0, ping_type, i);
        pings.insert(pings.end(), ping.begin(), ping.end());
    }
    size_t sent = 0;
    Bytes robot_1_heard, robot_2_heard;
    size_t pending = 0; // bytes of robot 1's link not yet answered
    for (int round = 0; round < enough_rounds; round++) {
        sent += tool.send_some(pings.data() + sent, pings.size() - sent);
        network.service(sent == pings.size() ? service_wait_ms : 0);
        // Robot 1 answers each whole ping it has read with a pong of its number.
        Bytes taken = take_received(*robot_1);
        robot_1_heard.insert(robot_1_heard.end(), taken.begin(), taken.end());
        pending += taken.size();
        for (; pending >= frame_bytes; pending -= frame_bytes) {
            const uint8_t *ping = robot_1_heard.data() + robot_1_heard.size() - pending;
            robot_sends(*robot_1,
                        event(robot_1_source, pong_type, uint16_t(ping[6] | (ping[7] << 8))));
        }
        Bytes heard = take_received(*robot_2);
        robot_2_heard.insert(robot_2_heard.end(), heard.begin(), heard.end());
        tool.collect();
        listener.collect();
        if (listener.received().size() == 2 * pings.size() &&
            tool.received().size() == pings.size() && robot_2_heard.size() == 2 * pings.size())
            break;
    }

    const std::vector<uint16_t> expected = zero_to(event_count);
    EXPECT_EQ(numbers_of(robot_1_heard, ping_type), expected) << "robot 1's pings";
    EXPECT_EQ(numbers_of(robot_2_heard, ping_type), expected) << "robot 2's pings";
    EXPECT_EQ(numbers_of(robot_2_heard, pong_type), expected) << "robot 2's pongs";
    EXPECT_EQ(numbers_of(tool.received(), pong_type), expected) << "the tool's pongs";
    EXPECT_EQ(numbers_of(listener.received(), ping_type), expected) << "the listener's pings";
    EXPECT_EQ(numbers_of(listener.received(), pong_type), expected) << "the listener's pongs";
    EXPECT_EQ(tool.received().size(), pings.size()) << "the tool hears no ping of its own";
}
