// epuck-emu's --robot-ports end to end, seen by the console: on a robot's own
// port a tool finds that robot alone, as over a direct Bluetooth link, while
// the shared port still shows the whole group. In flat mode the robots are in
// node id order; in arena mode in the arena file's order, whatever their ids.

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <netinet/in.h>
#include <sstream>
#include <stdexcept>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>

#include "console_support.hpp"

using namespace console_test;

namespace
{

// How many times to look for a free range of ports before giving up.
constexpr int port_range_attempts = 20;
constexpr unsigned highest_port = 65535;

// The first of `count` consecutive loopback ports that nothing uses now: a
// port the system picks, and the following ones if they can be bound too.
uint16_t find_free_ports(unsigned count)
{
    for (int attempt = 0; attempt < port_range_attempts; attempt++) {
        uint16_t first = find_free_port();
        if (first + count - 1 > highest_port)
            continue;
        std::vector<int> held;
        bool all_free = true;
        for (unsigned i = 0; i < count && all_free; i++) {
            int fd = socket(AF_INET, SOCK_STREAM, 0);
            sockaddr_in address{};
            address.sin_family = AF_INET;
            address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
            address.sin_port = htons(uint16_t(first + i));
            all_free = fd >= 0 &&
                       bind(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0 &&
                       !is_listening(uint16_t(first + i));
            if (fd >= 0)
                held.push_back(fd);
        }
        for (int fd : held)
            close(fd);
        if (all_free)
            return first;
    }
    throw std::runtime_error("no range of free ports");
}

std::string target_of(uint16_t port)
{
    return "tcp:localhost;" + std::to_string(port);
}

bool contains(const std::string &text, const std::string &part)
{
    return text.find(part) != std::string::npos;
}

// The node ids that `aseba nodes` lists on `target`, in its order.
std::vector<int> node_ids(const std::string &target, const ScratchFolder &scratch)
{
    CommandResult nodes = run_console({ "-t", target, "nodes" }, scratch.path());
    EXPECT_EQ(nodes.exit_code, 0) << nodes.err;
    std::vector<int> ids;
    for (const std::string &line : lines_of(nodes.out)) {
        EXPECT_TRUE(contains(line, "\"e-puck\"")) << line;
        const std::string head = "node ";
        if (line.compare(0, head.size(), head) == 0)
            ids.push_back(std::stoi(line.substr(head.size())));
        else
            ADD_FAILURE() << "not a node line: " << line;
    }
    return ids;
}

std::string read_text(const std::string &path)
{
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

// Waits until the file at `path` contains `part`, for a few seconds at most.
bool wait_for_text(const std::string &path, const std::string &part)
{
    const auto limit = std::chrono::seconds(5);
    const auto interval = std::chrono::milliseconds(20);
    auto deadline = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < deadline) {
        if (contains(read_text(path), part))
            return true;
        std::this_thread::sleep_for(interval);
    }
    return false;
}

} // namespace

TEST(RobotPorts, EachRobotAloneOnItsPortInFlatMode)
{
    ScratchFolder scratch;
    const unsigned robots = 3;
    uint16_t base = find_free_ports(robots);
    Emulator emulator(robots, { "--robot-ports", std::to_string(base) });

    EXPECT_EQ(node_ids(emulator.target(), scratch), (std::vector<int>{ 1, 2, 3 }));
    EXPECT_EQ(node_ids(target_of(uint16_t(base + 1)), scratch), std::vector<int>{ 2 });
    EXPECT_EQ(node_ids(target_of(base), scratch), std::vector<int>{ 1 });

    // Commands work over the direct link: write robot 2's LEDs there, read
    // them back on the shared port.
    CommandResult write =
      run_console({ "-t", target_of(uint16_t(base + 1)), "vars", "leds[1]=9" }, scratch.path());
    ASSERT_EQ(write.exit_code, 0) << write.err;
    CommandResult read =
      run_console({ "-t", emulator.target(), "vars", "leds[1]", "--node", "2" }, scratch.path());
    EXPECT_EQ(read.out, "leds[1] = 9\n") << read.err;
}

// Debian's asebadump, an independent decoder, on robot 2's port while the
// console asks the shared port for the nodes: every robot answers, and the
// dump shows robot 2's answers alone.
TEST(RobotPorts, ReferenceDumpOnARobotPortSeesThatRobotOnly)
{
    ASSERT_TRUE(in_path("asebadump"))
      << "Debian's aseba tools are not installed: run scripts/install-deps.sh";
    ScratchFolder scratch;
    const unsigned robots = 3;
    uint16_t base = find_free_ports(robots);
    Emulator emulator(robots, { "--robot-ports", std::to_string(base) });
    std::string log = scratch.path() + "/dump.log";
    ReferenceProgram dump({ "asebadump", target_of(uint16_t(base + 1)) }, {}, log);
    ASSERT_TRUE(wait_for_text(log, "connection created")) << read_text(log);

    EXPECT_EQ(node_ids(emulator.target(), scratch).size(), robots);
    EXPECT_TRUE(wait_for_text(log, "node present from 2")) << read_text(log);
    std::string dumped = read_text(log);
    EXPECT_FALSE(contains(dumped, "from 1 ")) << dumped;
    EXPECT_FALSE(contains(dumped, "from 3 ")) << dumped;
    // The console's requests (source 0) went to the bus, not to this link.
    EXPECT_FALSE(contains(dumped, "from 0 ")) << dumped;
}

TEST(RobotPorts, ArenaRobotsTakePortsInFileOrder)
{
    ScratchFolder scratch;
    // Node ids out of order: the ports follow the file, not the ids.
    std::string arena = scratch.write("two.arena",
                                      "size 100 100\n"
                                      "robot 7 20 20 0\n"
                                      "robot 4 80 80 180\n");
    const unsigned robots = 2;
    uint16_t base = find_free_ports(robots);
    // In real time: the emulator's time limit is in simulated seconds.
    Emulator emulator(
      robots, { "--arena", arena, "--speed", "realtime", "--robot-ports", std::to_string(base) });

    EXPECT_EQ(node_ids(emulator.target(), scratch).size(), 2u);
    EXPECT_EQ(node_ids(target_of(base), scratch), std::vector<int>{ 7 });
    EXPECT_EQ(node_ids(target_of(uint16_t(base + 1)), scratch), std::vector<int>{ 4 });
}

TEST(RobotPorts, RangeBeyondTheLastPortIsRefused)
{
    // The console is not involved: epuck-emu refuses before listening.
    EXPECT_THROW(Emulator(2, { "--robot-ports", "65535" }), std::runtime_error);
}
