// Run-time control of the arena (tools/emulator/arena_control.hpp): the
// commands' effects as the firmware reads them, their mistakes, and the
// control port answering a client over loopback, line by line.

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <chrono>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <string>
#include <tuple>

#include "arena_test_support.hpp"
#include "tools/emulator/arena_control.hpp"
#include "tools/emulator/control_port.hpp"

using namespace aseba::arena;
using arena_test::compile;
using arena_test::variables;

namespace
{

constexpr double pi = 3.14159265358979323846;

Arena three_robots()
{
    Arena arena;
    arena.robots = { { 1, 20, 50, 0 }, { 2, 50, 50, 0 }, { 3, 80, 50, 0 } };
    return arena;
}

bool starts_with(const std::string &text, const std::string &start)
{
    return text.compare(0, start.size(), start) == 0;
}

} // namespace

TEST(ArenaControl, SelectorAndRemoteCommandsReachTheFirmware)
{
    ArenaSimulation simulation(three_robots(), 1, {});
    simulation.run_for(0.05);
    EXPECT_EQ(run_control_command(simulation, "selector 2 7"), "ok selector of robot 2 at 7");
    EXPECT_EQ(run_control_command(simulation, "rc5 3 13"),
              "ok rc5 command 13 (address 0) to robot 3");
    simulation.run_for(0.05);
    EXPECT_EQ(variables(simulation, 0).selector[0], 0);
    EXPECT_EQ(variables(simulation, 1).selector[0], 7);
    EXPECT_EQ(variables(simulation, 2).rc5[0], 13);
    EXPECT_EQ(variables(simulation, 0).rc5[0], 0);

    EXPECT_EQ(run_control_command(simulation, "  selector   all 12 "),
              "ok selector of every robot at 12");
    EXPECT_EQ(run_control_command(simulation, "rc5 all 32 5"),
              "ok rc5 command 32 (address 5) to every robot");
    simulation.run_for(0.05);
    for (size_t robot = 0; robot < 3; robot++) {
        EXPECT_EQ(variables(simulation, robot).selector[0], 12);
        EXPECT_EQ(variables(simulation, robot).rc5[0], 32);
    }
    std::string status = run_control_command(simulation, "status");
    EXPECT_TRUE(starts_with(status, "ok time 0.15 s; robot 1: selector 12, battery 4.2")) << status;
    EXPECT_NE(status.find("robot 3: selector 12"), std::string::npos) << status;
    EXPECT_TRUE(starts_with(run_control_command(simulation, "help"), "ok commands: selector"));
}

class ControlMistakes : public testing::TestWithParam<std::pair<const char *, const char *>>
{
};

TEST_P(ControlMistakes, AreAnsweredWithAnErrorAndChangeNothing)
{
    ArenaSimulation simulation(three_robots(), 1, {});
    std::string answer = run_control_command(simulation, GetParam().first);
    EXPECT_TRUE(starts_with(answer, "error: ")) << answer;
    EXPECT_NE(answer.find(GetParam().second), std::string::npos) << answer;
    for (size_t robot = 0; robot < 3; robot++)
        EXPECT_EQ(simulation.world().selector(robot), 0);
}

INSTANTIATE_TEST_SUITE_P(
  Commands,
  ControlMistakes,
  testing::Values(std::pair{ "", "empty command" },
                  std::pair{ "teleport 1 2", "unknown command" },
                  std::pair{ "selector 1", "wrong number of words" },
                  std::pair{ "selector 9 3", "no robot answers to node id 9" },
                  std::pair{ "selector 1 16", "POSITION is a whole number from 0 to 15" },
                  std::pair{ "selector 1 -1", "not '-1'" },
                  std::pair{ "selector one 1", "ROBOT (a node id, or all)" },
                  std::pair{ "rc5 1 64", "COMMAND is a whole number from 0 to 63" },
                  std::pair{ "rc5 all 12 32", "ADDRESS is a whole number from 0 to 31" },
                  std::pair{ "rc5 all 1.5", "not '1.5'" }));

namespace
{

// A client of the control port on loopback.
class Client
{
  public:
    explicit Client(uint16_t port)
    {
        socket_ = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_port = htons(port);
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        connected_ =
          ::connect(socket_, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0;
    }
    ~Client()
    {
        ::close(socket_);
    }
    bool connected() const
    {
        return connected_;
    }
    void send(const std::string &text)
    {
        ASSERT_EQ(::send(socket_, text.data(), text.size(), 0), ssize_t(text.size()));
    }
    // The next answer line, servicing `port` meanwhile; "" after 5 s or when
    // the port closed the connection.
    std::string line(ControlPort &port)
    {
        auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(5);
        while (std::chrono::steady_clock::now() < give_up) {
            size_t end = received_.find('\n');
            if (end != std::string::npos) {
                std::string line = received_.substr(0, end);
                received_.erase(0, end + 1);
                return line;
            }
            port.service();
            char buffer[256];
            ssize_t count = ::recv(socket_, buffer, sizeof buffer, MSG_DONTWAIT);
            if (count == 0)
                return "";
            if (count > 0)
                received_.append(buffer, size_t(count));
            else
                ::usleep(1000);
        }
        return "";
    }

  private:
    int socket_ = -1;
    bool connected_ = false;
    std::string received_;
};

} // namespace

TEST(ControlPort, AnswersEachLineOnLoopback)
{
    ArenaSimulation simulation(three_robots(), 1, {});
    ControlPort port(
      0, [&](const std::string &line) { return run_control_command(simulation, line); });
    ASSERT_NE(port.port(), 0);
    Client client(port.port());
    ASSERT_TRUE(client.connected());
    // Two commands in one packet, a blank line (no answer) and a CR LF end.
    client.send("selector 3 4\n\nrc5 all 1\r\n");
    EXPECT_EQ(client.line(port), "ok selector of robot 3 at 4");
    EXPECT_EQ(client.line(port), "ok rc5 command 1 (address 0) to every robot");
    EXPECT_EQ(simulation.world().selector(2), 4);
    client.send("sel");
    client.send("ector 1 2\n");
    EXPECT_EQ(client.line(port), "ok selector of robot 1 at 2");
    EXPECT_EQ(port.client_count(), 1u);
}

TEST(ControlPort, LetsGoOfAClientWhoseLineIsTooLong)
{
    ArenaSimulation simulation(three_robots(), 1, {});
    ControlPort port(
      0, [&](const std::string &line) { return run_control_command(simulation, line); });
    Client talker(port.port());
    talker.send(std::string(ControlPort::longest_line + 10, 'x'));
    EXPECT_EQ(talker.line(port), "error: a command line is at most 1024 characters");
    EXPECT_EQ(talker.line(port), "") << "still connected";
    // Others are still served.
    Client other(port.port());
    other.send("help\n");
    EXPECT_TRUE(starts_with(other.line(port), "ok commands"));
}

// A web page can make the browser send a request to any port of this
// computer, and choose its body (fetch, mode no-cors): the lines of a body
// turned selectors and pressed remote keys. A client that speaks HTTP is let
// go at its request line, before any line of its body runs.
TEST(ControlPort, ARequestOfABrowserRunsNoCommand)
{
    ArenaSimulation simulation(three_robots(), 1, {});
    ControlPort port(
      0, [&](const std::string &line) { return run_control_command(simulation, line); });
    for (const char *request_line : { "POST / HTTP/1.1", "GET /?x HTTP/1.0", "PUT /a HTTP/1.1" }) {
        SCOPED_TRACE(request_line);
        Client browser(port.port());
        browser.send(std::string(request_line) +
                     "\r\nHost: 127.0.0.1\r\nContent-Type: text/plain\r\n\r\nselector 3 4\n");
        EXPECT_EQ(browser.line(port), "") << "answered, or still connected";
        EXPECT_EQ(simulation.world().selector(2), 0);
    }
    Client tool(port.port());
    tool.send("selector 3 4\n");
    EXPECT_EQ(tool.line(port), "ok selector of robot 3 at 4");
}

TEST(ControlPort, RefusesAPortInUse)
{
    ControlPort first(0, [](const std::string &) { return std::string("ok"); });
    EXPECT_THROW(ControlPort(first.port(), [](const std::string &) { return std::string("ok"); }),
                 std::runtime_error);
}

// examples/behaviours.aesl, the lesson the selector and the remote are for:
// the selector chooses the behaviour, a digit key on the remote another.
TEST(ArenaControl, LessonSwitchesBehavioursWithTheSelectorAndTheRemote)
{
    Arena arena;
    arena.robots = { { 1, 50, 50, 0, 2 } }; // selector at 2: turn on the spot
    ArenaSimulation simulation(arena, 1, compile("examples/behaviours.aesl"));
    auto moved = [&simulation](double seconds) {
        simulation.run_for(0.2); // the key or the selector is taken
        Pose before = simulation.world().pose(0);
        simulation.run_for(seconds);
        Pose after = simulation.world().pose(0);
        return std::pair{ std::hypot(after.x - before.x, after.y - before.y),
                          std::abs(std::remainder(after.heading - before.heading, 2 * pi)) };
    };
    auto [distance, turn] = moved(0.5);
    EXPECT_LT(distance, 0.5);
    EXPECT_GT(turn, 0.5) << "not turning";
    EXPECT_EQ(variables(simulation, 0).leds[2], 1);

    // Key 1: wander, at 500 steps/s (6.4 cm/s) in the open.
    EXPECT_TRUE(starts_with(run_control_command(simulation, "rc5 1 1"), "ok"));
    std::tie(distance, turn) = moved(1);
    EXPECT_NEAR(distance, 6.4, 0.5);
    EXPECT_EQ(variables(simulation, 0).leds[1], 1);

    // Key 0: stop.
    EXPECT_TRUE(starts_with(run_control_command(simulation, "rc5 1 0"), "ok"));
    std::tie(distance, turn) = moved(0.5);
    EXPECT_EQ(distance, 0);
    EXPECT_EQ(turn, 0);
    EXPECT_EQ(variables(simulation, 0).leds[0], 1);

    // The selector turned to 1: wander again.
    EXPECT_TRUE(starts_with(run_control_command(simulation, "selector 1 1"), "ok"));
    std::tie(distance, turn) = moved(1);
    EXPECT_NEAR(distance, 6.4, 0.5);
}
