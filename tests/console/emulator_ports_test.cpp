// epuck-emu's ports: who reaches them (this computer only, unless told
// otherwise), and a tool that opens connections by the hundred: each port
// holds its own number of them, within the descriptors the process may
// have, so that filling one leaves the others reachable
// (tools/connections/port_limit.hpp).

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "console_support.hpp"

using namespace console_test;

namespace
{

constexpr Milliseconds START_LIMIT{ 15000 };

// A connection to `port` of `host`; -1 when refused.
int connect_to(uint16_t port, const char *host = "127.0.0.1")
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    inet_pton(AF_INET, host, &address.sin_addr);
    if (fd >= 0 && connect(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0)
        return fd;
    if (fd >= 0)
        close(fd);
    return -1;
}

// The first line `fd` receives within `limit`, or "".
std::string first_line(int fd, Milliseconds limit)
{
    std::string received;
    auto deadline = std::chrono::steady_clock::now() + limit;
    while (received.find('\n') == std::string::npos) {
        auto left =
          std::chrono::duration_cast<Milliseconds>(deadline - std::chrono::steady_clock::now());
        pollfd waiting{ fd, POLLIN, 0 };
        char buffer[256];
        ssize_t count = 0;
        if (left.count() <= 0 || poll(&waiting, 1, int(left.count())) <= 0 ||
            (count = read(fd, buffer, sizeof buffer)) <= 0)
            return "";
        received.append(buffer, size_t(count));
    }
    return received.substr(0, received.find('\n'));
}

// Distinct free ports of the loopback.
std::vector<uint16_t> free_ports(size_t count)
{
    std::vector<uint16_t> ports;
    while (ports.size() < count) {
        uint16_t port = find_free_port();
        if (std::find(ports.begin(), ports.end(), port) == ports.end())
            ports.push_back(port);
    }
    return ports;
}

// epuck-emu with `options` under a shell's `limits` (ulimit), once its
// `ports` listen.
std::unique_ptr<ReferenceProgram> start_emulator(const std::string &options,
                                                 const std::string &limits,
                                                 const std::vector<uint16_t> &ports,
                                                 const ScratchFolder &scratch)
{
    std::string command = limits + "exec " + program_path("epuck-emu") +
                          " --arena default --duration 120 --quiet " + options;
    auto emulator =
      std::make_unique<ReferenceProgram>(std::vector<std::string>{ "sh", "-c", command },
                                         std::vector<std::string>{},
                                         scratch.path() + "/epuck-emu.log");
    auto deadline = std::chrono::steady_clock::now() + START_LIMIT;
    auto all_listen = [&] {
        return std::all_of(
          ports.begin(), ports.end(), [](uint16_t port) { return is_listening(port); });
    };
    while (!all_listen() && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(Milliseconds(50));
    if (!all_listen())
        throw std::runtime_error("epuck-emu did not start: " + command);
    return emulator;
}

} // namespace

// Aseba has no authentication: every port of epuck-emu is on the loopback
// unless --listen says otherwise, where other computers cannot reach it
// (127.0.0.2 is this computer too, but not the address 127.0.0.1 listens
// on, as another computer's address would not be). The control port is on
// the loopback always.
TEST(EmulatorPorts, EveryPortIsOnTheLoopbackUnlessToldOtherwise)
{
    ScratchFolder scratch;
    std::vector<uint16_t> ports = free_ports(4); // network, control, feed, the robot's own
    std::string options = "--robots 1 --port " + std::to_string(ports[0]) + " --control " +
                          std::to_string(ports[1]) + " --arena-feed " + std::to_string(ports[2]) +
                          " --robot-ports " + std::to_string(ports[3]);
    for (bool open : { false, true }) {
        SCOPED_TRACE(open ? "--listen 0.0.0.0" : "default");
        auto emulator =
          start_emulator(options + (open ? " --listen 0.0.0.0" : ""), "", ports, scratch);
        for (uint16_t port : { ports[0], ports[2], ports[3] }) {
            int local = connect_to(port);
            int other = connect_to(port, "127.0.0.2");
            EXPECT_GE(local, 0) << port;
            EXPECT_EQ(other >= 0, open) << port;
            for (int fd : { local, other })
                if (fd >= 0)
                    close(fd);
        }
        int control = connect_to(ports[1], "127.0.0.2");
        EXPECT_LT(control, 0);
        if (control >= 0)
            close(control);
    }
}

// The arena feed had no cap: 400 viewers under a limit of 256 descriptors
// left epuck-emu none to accept with, and no tool could reach the network
// or the control port any more.
TEST(EmulatorPorts, AFloodOfArenaViewersLeavesTheNetworkAndControlPortsReachable)
{
    ScratchFolder scratch;
    std::vector<uint16_t> ports = free_ports(3);
    uint16_t network = ports[0], control = ports[1], feed = ports[2];
    auto emulator =
      start_emulator("--robots 2 --port " + std::to_string(network) + " --control " +
                       std::to_string(control) + " --arena-feed " + std::to_string(feed),
                     "ulimit -n 256 && ",
                     ports,
                     scratch);

    std::vector<int> viewers;
    for (int i = 0; i < 400; i++)
        if (int fd = connect_to(feed); fd >= 0)
            viewers.push_back(fd);
    EXPECT_EQ(viewers.size(), 400u);

    CommandResult nodes =
      run_console({ "-t", "tcp:localhost;" + std::to_string(network), "nodes" }, scratch.path());
    EXPECT_EQ(nodes.exit_code, 0) << nodes.err;
    EXPECT_EQ(lines_of(nodes.out).size(), 2u) << nodes.out;

    int controller = connect_to(control);
    ASSERT_GE(controller, 0);
    const char status[] = "status\n";
    ASSERT_EQ(write(controller, status, sizeof status - 1), ssize_t(sizeof status - 1));
    EXPECT_NE(first_line(controller, Milliseconds(10000)), "");
    close(controller);
    for (int fd : viewers)
        close(fd);
    EXPECT_TRUE(emulator->running());
}

// Under a limit of open files too low for all its ports, epuck-emu stops at
// once and says what it needs, rather than running with ports that could
// not all accept.
TEST(EmulatorPorts, TooFewOpenFilesForItsPortsIsSaidAtStart)
{
    ScratchFolder scratch;
    std::vector<uint16_t> ports = free_ports(2);
    std::string errors = scratch.path() + "/errors";
    std::string command = "ulimit -n 100 && exec " + program_path("epuck-emu") +
                          " --robots 2 --duration 1 --quiet --port " + std::to_string(ports[0]) +
                          " --robot-ports " + std::to_string(ports[1]) + " > /dev/null 2> " +
                          errors;
    int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1);
    std::ifstream file(errors);
    std::string said((std::istreambuf_iterator<char>(file)), {});
    EXPECT_NE(said.find("epuck-emu: the ports need "), std::string::npos) << said;
    EXPECT_NE(said.find("ulimit -n"), std::string::npos) << said;
}
