// The tools and the simulated network under load, against an epuck-emu it
// starts on a free loopback port and stops itself (by its recorded pid):
//
//   bench-network load RUNS
//       epuck-emu --robots 6; `aseba load examples/paper-annex.aesl` RUNS
//       times (edit to running: start the console, connect, discover and
//       describe the six robots, compile, upload, run). Prints the median,
//       the lowest and the highest wall-clock time in ms.
//
//   bench-network connections CYCLES
//       epuck-emu --robots 1; CYCLES connect/close cycles on its port, one
//       after the other; then a GET_VARIABLES must still be answered. Prints
//       the seconds the cycles took.
//
//   bench-network flood SECONDS
//       epuck-emu --robots 6; one client sends user events as fast as the
//       network takes them for SECONDS, while another reads a variable of
//       robot 1 every 50 ms. Prints epuck-emu's resident memory before the
//       flood and its peak (kB, VmRSS and VmHWM), the flood's megabytes, and
//       the other client's median and longest round trip in ms, before and
//       during the flood.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <netinet/in.h>
#include <stdexcept>
#include <string>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "tests/interop/child_process.hpp"
#include "tests/interop/interop_support.hpp"
#include "tools/client/network.hpp"

namespace
{

using Clock = std::chrono::steady_clock;
using Milliseconds = std::chrono::milliseconds;
using interop::ChildProcess;
using interop::EmulatedRobots;
using interop::ScratchFolder;

constexpr const char *paper_annex_project = "examples/paper-annex.aesl";
constexpr unsigned group_size = 6;
constexpr Milliseconds answer_timeout{ 5000 };
constexpr Milliseconds probe_interval{ 50 };
constexpr size_t flood_chunk_events = 4096;

double milliseconds_since(Clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> values)
{
    if (values.empty())
        return 0;
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

int connect_to(uint16_t port)
{
    int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(port);
    if (fd < 0 || connect(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0)
        throw std::runtime_error("cannot connect to port " + std::to_string(port));
    return fd;
}

// A kB figure of /proc/PID/status (VmRSS, VmHWM).
long status_kilobytes(pid_t pid, const std::string &field)
{
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind(field + ":", 0) == 0)
            return std::strtol(line.c_str() + field.size() + 1, nullptr, 10);
    return -1;
}

int bench_load(int runs)
{
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, group_size);
    std::string console = interop::our_program_path("aseba");
    std::vector<double> times;
    for (int run = 0; run < runs; run++) {
        auto start = Clock::now();
        ChildProcess load({ console, "-t", robots.target(), "load", paper_annex_project },
                          scratch.file("load.log"));
        if (!load.wait_for_exit(answer_timeout) || load.exit_code() != 0)
            throw std::runtime_error("aseba load failed: " + load.exit_description() + "\n" +
                                     interop::read_file(scratch.file("load.log")));
        times.push_back(milliseconds_since(start));
    }
    std::printf("%.1f %.1f %.1f\n",
                median(times),
                *std::min_element(times.begin(), times.end()),
                *std::max_element(times.begin(), times.end()));
    return 0;
}

int bench_connections(int cycles)
{
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, 1);
    auto start = Clock::now();
    for (int cycle = 0; cycle < cycles; cycle++)
        close(connect_to(robots.port()));
    double seconds = milliseconds_since(start) / 1000;
    aseba::client::Network network(answer_timeout);
    network.connect(robots.target());
    network.discover();
    network.read_variables(network.select("1").at(0), 0, 1);
    std::printf("%.3f\n", seconds);
    return 0;
}

int bench_flood(double seconds)
{
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, group_size);
    aseba::client::Network network(answer_timeout);
    network.connect(robots.target());
    network.discover();
    aseba::client::NodeKey robot = network.select("1").at(0);
    auto probe = [&](double duration_seconds) {
        std::vector<double> times;
        auto end = Clock::now() + std::chrono::duration<double>(duration_seconds);
        while (Clock::now() < end) {
            auto start = Clock::now();
            network.read_variables(robot, 0, 1);
            times.push_back(milliseconds_since(start));
            network.wait_until([] { return false; }, probe_interval);
        }
        return times;
    };
    std::vector<double> idle = probe(1.0);
    long rss_before = status_kilobytes(robots.process().pid(), "VmRSS");

    // User event 0 with one argument, from a host.
    const std::vector<uint8_t> event = { 2, 0, 0, 0, 0, 0, 1, 0 };
    std::vector<uint8_t> chunk;
    for (size_t i = 0; i < flood_chunk_events; i++)
        chunk.insert(chunk.end(), event.begin(), event.end());
    std::atomic<bool> flooding{ true };
    std::atomic<uint64_t> flooded{ 0 };
    int flooder = connect_to(robots.port());
    std::thread flood([&] {
        size_t offset = 0;
        while (flooding) {
            ssize_t sent =
              send(flooder, chunk.data() + offset, chunk.size() - offset, MSG_NOSIGNAL);
            if (sent <= 0)
                break; // dropped by the network
            flooded += uint64_t(sent);
            offset = (offset + size_t(sent)) % chunk.size();
        }
    });
    // Blocking sends return once the network stops reading: make them time
    // out so that the thread sees the end.
    timeval timeout{ 0, 100000 };
    setsockopt(flooder, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
    std::vector<double> flooded_times = probe(seconds);
    long rss_during = status_kilobytes(robots.process().pid(), "VmRSS");
    long rss_peak = status_kilobytes(robots.process().pid(), "VmHWM");
    flooding = false;
    flood.join();
    close(flooder);
    std::printf("%ld %ld %ld %.1f %.2f %.2f %.2f %.2f\n",
                rss_before,
                rss_during,
                rss_peak,
                double(flooded) / 1e6,
                median(idle),
                *std::max_element(idle.begin(), idle.end()),
                median(flooded_times),
                *std::max_element(flooded_times.begin(), flooded_times.end()));
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    try {
        std::string mode = argc > 1 ? argv[1] : "";
        if (mode == "load" && argc == 3)
            return bench_load(std::atoi(argv[2]));
        if (mode == "connections" && argc == 3)
            return bench_connections(std::atoi(argv[2]));
        if (mode == "flood" && argc == 3)
            return bench_flood(std::atof(argv[2]));
        std::fprintf(stderr,
                     "usage: bench-network load RUNS | connections CYCLES | flood SECONDS\n");
        return 2;
    } catch (const std::exception &error) {
        std::fprintf(stderr, "bench-network: %s\n", error.what());
        return 1;
    }
}
