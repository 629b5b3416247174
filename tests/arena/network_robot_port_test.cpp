// A robot's own port (host::Network::listen_robot), on bare host boards and
// loopback sockets: a client there is linked to that robot alone, as a tool
// linked to one e-puck by Bluetooth. It hears that robot's frames and no
// other's, and what it sends reaches that robot and nothing else; the robot's
// frames still reach the shared bus. Frames are built by hand from
// protocol.md §2 (length of the payload, source, type, payload, little
// endian).

#include <chrono>
#include <memory>
#include <stdexcept>
#include <vector>

#include "network_test_support.hpp"
#include "tools/emulator/network.hpp"

namespace
{

using namespace network_test;
using Clock = std::chrono::steady_clock;

// User event 0 with one argument, from node 1 and from node 2.
const Bytes event_from_robot_1 = { 2, 0, 1, 0, 0, 0, 11, 0 };
const Bytes event_from_robot_2 = { 2, 0, 2, 0, 0, 0, 22, 0 };
// "node present" (0x900C) answers, as robot 2 gives them to LIST_NODES.
const Bytes robot_2_present = { 2, 0, 2, 0, 0x0C, 0x90, 5, 0 };
// GET_DESCRIPTION (0xA001) for node 2 and LIST_NODES (0xA000), from a tool
// (source 0).
const Bytes get_description_2 = { 4, 0, 0, 0, 0x01, 0xA0, 2, 0, 5, 0 };
const Bytes list_nodes = { 2, 0, 0, 0, 0x00, 0xA0, 5, 0 };
// A user event a tool emits (event 3, no argument).
const Bytes tool_event = { 0, 0, 0, 0, 3, 0 };

// How long the tests wait for bytes that should come, and for bytes that
// should not (a loopback socket delivers in far less).
constexpr auto arrival_limit = std::chrono::seconds(2);
constexpr auto silence_period = std::chrono::milliseconds(100);
constexpr int service_wait_ms = 1;

struct NetworkRobotPort : testing::Test {
    std::unique_ptr<hal_board> robot_1 = std::make_unique<hal_board>();
    std::unique_ptr<hal_board> robot_2 = std::make_unique<hal_board>();
    aseba::host::Network network;
    uint16_t shared_port = 0;
    uint16_t robot_2_port = 0;

    void SetUp() override
    {
        host_board_init(robot_1.get(), nullptr, nullptr);
        host_board_init(robot_2.get(), nullptr, nullptr);
        network.attach(robot_1.get());
        network.attach(robot_2.get());
        // Port 0: the system picks free ports.
        shared_port = network.listen(0);
        robot_2_port = network.listen_robot(robot_2.get(), 0);
    }

    // Services the network until `done` holds or the time limit passes;
    // returns whether it held.
    template<typename Done>
    bool serve_until(Done done, std::chrono::milliseconds limit = arrival_limit)
    {
        auto deadline = Clock::now() + limit;
        while (Clock::now() < deadline) {
            network.service(service_wait_ms);
            if (done())
                return true;
        }
        return done();
    }

    // Services the network for a while, long enough for any stray frame.
    void serve_a_while()
    {
        serve_until([] { return false; }, silence_period);
    }

    void accept_clients(size_t count)
    {
        ASSERT_TRUE(serve_until([&] { return network.client_count() == count; }));
    }
};

} // namespace

TEST_F(NetworkRobotPort, DirectClientHearsItsRobotOnly)
{
    ToolSocket direct(robot_2_port);
    ToolSocket shared(shared_port);
    accept_clients(2);

    robot_sends(*robot_1, event_from_robot_1);
    robot_sends(*robot_2, event_from_robot_2);
    ASSERT_TRUE(serve_until([&] {
        direct.collect();
        shared.collect();
        return direct.received().size() >= event_from_robot_2.size() &&
               shared.received().size() >= 2 * event_from_robot_1.size();
    }));
    serve_a_while();
    direct.collect();
    shared.collect();
    // Robot 1's event came first: it would lead the direct client's stream.
    EXPECT_EQ(direct.received(), event_from_robot_2);
    EXPECT_EQ(shared.received(), event_from_robot_1 + event_from_robot_2);
    // The robots still hear each other on the shared bus.
    EXPECT_EQ(take_received(*robot_1), event_from_robot_2);
    EXPECT_EQ(take_received(*robot_2), event_from_robot_1);
}

TEST_F(NetworkRobotPort, DirectClientReachesItsRobotOnly)
{
    ToolSocket direct(robot_2_port);
    ToolSocket shared(shared_port);
    accept_clients(2);

    direct.send(get_description_2 + tool_event);
    Bytes expected = get_description_2 + tool_event;
    ASSERT_TRUE(serve_until([&] { return robot_2->receive_count >= expected.size(); }));
    serve_a_while();
    shared.collect();
    EXPECT_EQ(take_received(*robot_2), expected);
    EXPECT_TRUE(take_received(*robot_1).empty()) << "not on the shared bus";
    EXPECT_TRUE(shared.received().empty()) << "the shared port's tools do not hear it";
}

TEST_F(NetworkRobotPort, RobotAnswersReachDirectClientAndBus)
{
    ToolSocket direct(robot_2_port);
    ToolSocket shared(shared_port);
    accept_clients(2);

    direct.send(list_nodes);
    ASSERT_TRUE(serve_until([&] { return robot_2->receive_count >= list_nodes.size(); }));
    EXPECT_EQ(take_received(*robot_2), list_nodes);
    robot_sends(*robot_2, robot_2_present);
    ASSERT_TRUE(serve_until([&] {
        direct.collect();
        shared.collect();
        return direct.received().size() >= robot_2_present.size() &&
               shared.received().size() >= robot_2_present.size();
    }));
    EXPECT_EQ(direct.received(), robot_2_present);
    EXPECT_EQ(shared.received(), robot_2_present);
    EXPECT_EQ(take_received(*robot_1), robot_2_present);
}

TEST_F(NetworkRobotPort, SharedToolsDoNotReachDirectClients)
{
    ToolSocket direct(robot_2_port);
    ToolSocket shared(shared_port);
    accept_clients(2);

    shared.send(list_nodes);
    ASSERT_TRUE(serve_until([&] {
        return robot_1->receive_count >= list_nodes.size() &&
               robot_2->receive_count >= list_nodes.size();
    }));
    serve_a_while();
    direct.collect();
    EXPECT_TRUE(direct.received().empty()) << "a direct link carries its robot's frames only";
    EXPECT_EQ(take_received(*robot_1), list_nodes);
    EXPECT_EQ(take_received(*robot_2), list_nodes);
}

// The bus moves whole frames: a frame a direct client writes in pieces
// reaches the robot once complete, and not before.
TEST_F(NetworkRobotPort, DirectClientFramesArriveWhole)
{
    ToolSocket direct(robot_2_port);
    accept_clients(1);

    const size_t split = 3;
    direct.send(Bytes(get_description_2.begin(), get_description_2.begin() + split));
    serve_a_while();
    EXPECT_EQ(robot_2->receive_count, 0);
    direct.send(Bytes(get_description_2.begin() + split, get_description_2.end()));
    ASSERT_TRUE(serve_until([&] { return robot_2->receive_count >= get_description_2.size(); }));
    EXPECT_EQ(take_received(*robot_2), get_description_2);
}

TEST_F(NetworkRobotPort, RefusesBoardsNotOnTheNetwork)
{
    auto stranger = std::make_unique<hal_board>();
    host_board_init(stranger.get(), nullptr, nullptr);
    EXPECT_THROW(network.listen_robot(stranger.get(), 0), std::invalid_argument);
}
