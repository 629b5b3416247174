// The node benchmark, over loopback TCP, against a node process it starts on
// a free port and stops itself (by the pid it recorded):
//
//   bench-node emu [EVENTS]        epuck-emu with one robot (our node and firmware)
//   bench-node reference [EVENTS]  Debian's asebadummynode (the reference node library)
//   bench-node at-once [EVENTS]    a node that answers at once: this client's ceiling
//       prints: median round trip of GET_VARIABLES -> VARIABLES in us, the
//       mean in us, user events per second through a handler that answers
//       each `ping` with a `pong` (EVENTS of them, 20,000 unless given, at
//       least `event_window`; at most `event_window` in flight).
//       BENCH_NODE_UNDER: a command the node runs under (its words split at
//       spaces), for example valgrind's, to count the node's instructions.
//
//   bench-node serve-at-once PORT
//       the node of `at-once`: this program answering on PORT, GET_VARIABLES
//       with VARIABLES of zeros and each `ping` with a `pong`, with nothing
//       between its socket and the answer (no VM, no queue, no sleep).
//
//   bench-node simulator ROBOTS SECONDS
//       runs epuck-emu with ROBOTS robots running the paper's controller for
//       SECONDS and prints the CPU seconds it used per robot-second.
//
// Nothing else sits between the client and the node (asebadummynode serves
// one client); the client never sends GET_NODE_DESCRIPTION, which crashes
// asebadummynode (see the reference tools' pitfalls).

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>
#include <vector>

#include "tests/interop/child_process.hpp"
#include "tests/interop/interop_support.hpp"
#include "tools/client/wire.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "vm/node_protocol.h"
}

namespace
{

using aseba::client::Frame;
using Clock = std::chrono::steady_clock;

constexpr const char *emulator_path = "build/host/bin/epuck-emu";
constexpr const char *reference_node_path = "asebadummynode";
constexpr const char *paper_annex_project = "examples/paper-annex.aesl";
constexpr const char *emulator_lifetime_seconds = "120"; // a safety net; we stop it sooner
constexpr auto start_timeout = std::chrono::milliseconds(5000);
constexpr auto answer_timeout = std::chrono::milliseconds(2000);
constexpr long reads_between_clock_looks = 1024; // the spinning read's look at its timeout
constexpr uint16_t node_id = 1;                  // robot 1 of epuck-emu; dummynode-0 is node 1
constexpr uint16_t ping_event = 0;
constexpr uint16_t pong_event = 1;
constexpr int latency_rounds = 2000;
constexpr int warmup_rounds = 50;
constexpr uint16_t variables_read_words = 16;
constexpr int default_event_count = 20000;
constexpr int event_window = 16;
constexpr size_t bytecode_chunk_words = 256;
constexpr const char *ping_pong_program = "onevent ping\nemit pong\n";

// Port `port` of this computer's loopback interface.
sockaddr_in loopback_address(uint16_t port)
{
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return address;
}

// A TCP client of one node, with Nagle and delayed ACK off.
class Connection
{
  public:
    explicit Connection(uint16_t port)
    {
        socket_ = ::socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in address = loopback_address(port);
        if (socket_ < 0 ||
            ::connect(socket_, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0)
            throw std::runtime_error("cannot connect to port " + std::to_string(port));
        int on = 1;
        setsockopt(socket_, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
    }
    ~Connection()
    {
        ::close(socket_);
    }
    Connection(const Connection &) = delete;
    Connection &operator=(const Connection &) = delete;

    // Sends the frame `copies` times in one write.
    void send(uint16_t type, const std::vector<uint16_t> &words, int copies = 1)
    {
        Frame frame;
        frame.source = aseba::client::HOST_SOURCE;
        frame.type = type;
        for (uint16_t word : words) {
            frame.payload.push_back(static_cast<uint8_t>(word & 0xFF));
            frame.payload.push_back(static_cast<uint8_t>(word >> 8));
        }
        std::vector<uint8_t> one = aseba::client::serialize_frame(frame);
        std::vector<uint8_t> bytes;
        for (int copy = 0; copy < copies; copy++)
            bytes.insert(bytes.end(), one.begin(), one.end());
        if (::send(socket_, bytes.data(), bytes.size(), MSG_NOSIGNAL) !=
            static_cast<ssize_t>(bytes.size()))
            throw std::runtime_error("send failed");
    }

    // The next frame of `type`, skipping others; throws after the timeout.
    Frame receive(uint16_t type)
    {
        for (;;) {
            while (auto frame = frames_.next())
                if (frame->type == type)
                    return *frame;
            read_more(type);
        }
    }

    // Waits for frames of `type`, skipping others; returns how many came
    // with the first (those already read, at least one).
    int receive_some(uint16_t type)
    {
        for (;;) {
            int count = 0;
            while (auto frame = frames_.next())
                count += frame->type == type;
            if (count > 0)
                return count;
            read_more(type);
        }
    }

  private:
    // Reads what has come (waiting for it up to the timeout) into the frames.
    // The client spins on a read that does not block instead of sleeping in
    // one: woken from a blocking read, it was itself the limit (a node that
    // answers at once, `at-once`, ran no faster than epuck-emu), and the
    // figure measured the client rather than the nodes.
    void read_more(uint16_t type)
    {
        uint8_t buffer[4096];
        const auto deadline = Clock::now() + answer_timeout;
        ssize_t count;
        for (long reads = 1;; reads++) {
            count = ::recv(socket_, buffer, sizeof buffer, MSG_DONTWAIT);
            if (count >= 0 || (errno != EAGAIN && errno != EWOULDBLOCK))
                break;
            if (reads % reads_between_clock_looks == 0 && Clock::now() > deadline)
                throw std::runtime_error("no answer of type " + std::to_string(type));
        }
        if (count <= 0)
            throw std::runtime_error("the node closed the connection");
        frames_.feed(buffer, static_cast<size_t>(count));
        // Acknowledge at once: a waiting client must not see delayed ACKs.
        int on = 1;
        setsockopt(socket_, IPPROTO_TCP, TCP_QUICKACK, &on, sizeof on);
    }

    int socket_ = -1;
    aseba::client::FrameAssembler frames_;
};

// The words of BENCH_NODE_UNDER, none if it is not set.
const std::vector<std::string> &wrapper_words()
{
    static const std::vector<std::string> words = [] {
        const char *under = std::getenv("BENCH_NODE_UNDER");
        std::istringstream text(under ? under : "");
        std::vector<std::string> split;
        for (std::string word; text >> word;)
            split.push_back(word);
        return split;
    }();
    return words;
}

// This program's own path, to start it again as the node that answers at once.
std::string this_program()
{
    char path[4096];
    ssize_t length = ::readlink("/proc/self/exe", path, sizeof path - 1);
    if (length <= 0)
        throw std::runtime_error("cannot find this program's path");
    return std::string(path, static_cast<size_t>(length));
}

enum class NodeKind { Ours, Reference, AtOnce };

// The node process, started on a free port, stopped when this ends.
struct NodeProcess {
    interop::ScratchFolder scratch;
    uint16_t port = 0;
    std::unique_ptr<interop::ChildProcess> process;

    explicit NodeProcess(NodeKind kind, unsigned robots = 1, const char *load = nullptr)
    {
        port = interop::find_free_port();
        std::vector<std::string> argv;
        if (kind == NodeKind::Reference)
            argv = { reference_node_path, "-p", std::to_string(port), "0" };
        else if (kind == NodeKind::AtOnce)
            argv = { this_program(), "serve-at-once", std::to_string(port) };
        else {
            argv = { emulator_path,          "--port",     std::to_string(port),      "--robots",
                     std::to_string(robots), "--duration", emulator_lifetime_seconds, "--quiet" };
            if (load)
                argv.insert(argv.end(), { "--load", load });
        }
        argv.insert(argv.begin(), wrapper_words().begin(), wrapper_words().end());
        if (kind == NodeKind::Reference) {
            // A probe connection would make asebadummynode deaf once it
            // closes: wait for the line it prints when it listens instead.
            process = std::make_unique<interop::ChildProcess>(
              argv, scratch.file("node.log"), interop::OutputMode::ToPipe);
            auto line = process->read_line(start_timeout);
            if (!line || line->find("tcp:port=" + std::to_string(port)) == std::string::npos)
                throw std::runtime_error(process->command_line() + " does not listen");
            return;
        }
        process = std::make_unique<interop::ChildProcess>(argv, scratch.file("node.log"));
        if (!interop::wait_until_listening(port, start_timeout))
            throw std::runtime_error(process->command_line() + " does not listen");
    }
};

double median(std::vector<double> values)
{
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

void load_ping_pong(Connection &connection, const aseba::TargetDescription &target)
{
    aseba::CommonDefinitions definitions;
    definitions.events = { { "ping", 0 }, { "pong", 0 } };
    aseba::CompileResult program = aseba::compile(ping_pong_program, target, definitions);
    if (!program.ok)
        throw std::runtime_error("ping-pong program: " + program.error.message);
    for (size_t start = 0; start < program.bytecode.size(); start += bytecode_chunk_words) {
        size_t end = std::min(program.bytecode.size(), start + bytecode_chunk_words);
        std::vector<uint16_t> words{ node_id, static_cast<uint16_t>(start) };
        words.insert(words.end(),
                     program.bytecode.begin() + static_cast<long>(start),
                     program.bytecode.begin() + static_cast<long>(end));
        connection.send(NODE_MSG_SET_BYTECODE, words);
    }
    connection.send(NODE_MSG_RESET, { node_id });
    connection.send(NODE_MSG_RUN, { node_id });
}

int bench_node(NodeKind kind, int event_count)
{
    NodeProcess node(kind);
    Connection connection(node.port);

    std::vector<double> round_trips_us;
    for (int round = 0; round < warmup_rounds + latency_rounds; round++) {
        auto begin = Clock::now();
        connection.send(NODE_MSG_GET_VARIABLES, { node_id, 0, variables_read_words });
        connection.receive(NODE_MSG_VARIABLES);
        auto end = Clock::now();
        if (round >= warmup_rounds)
            round_trips_us.push_back(
              std::chrono::duration<double, std::micro>(end - begin).count());
    }
    double mean_us = 0;
    for (double value : round_trips_us)
        mean_us += value / static_cast<double>(round_trips_us.size());

    load_ping_pong(connection,
                   kind == NodeKind::Reference ? aseba::dummy_target() : aseba::epuck_target());
    int sent = 0;
    auto begin = Clock::now();
    // As many pings in flight as the window, the ones answered since the
    // last read sent again in one write: one write per ping made this client
    // the limit of both nodes (each about 145,000 events a second here).
    connection.send(ping_event, {}, event_window);
    sent = event_window;
    for (int answered = 0; answered < event_count;) {
        int count = connection.receive_some(pong_event);
        answered += count;
        int more = std::min(count, event_count - sent);
        if (more > 0) {
            connection.send(ping_event, {}, more);
            sent += more;
        }
    }
    double seconds = std::chrono::duration<double>(Clock::now() - begin).count();

    std::printf("%.1f\t%.1f\t%.0f\n", median(round_trips_us), mean_us, event_count / seconds);
    node.process->stop();
    return 0;
}

double children_cpu_seconds()
{
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    auto seconds = [](const timeval &time) { return time.tv_sec + time.tv_usec / 1e6; };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

int bench_simulator(unsigned robots, double seconds)
{
    double cpu_before = children_cpu_seconds();
    auto begin = Clock::now();
    {
        NodeProcess node(NodeKind::Ours, robots, paper_annex_project);
        while (std::chrono::duration<double>(Clock::now() - begin).count() < seconds)
            usleep(10000);
        node.process->stop(); // reaped: its CPU time now counts
    }
    double wall = std::chrono::duration<double>(Clock::now() - begin).count();
    double cpu = children_cpu_seconds() - cpu_before;
    std::printf("%.6f\t%.3f\t%.3f\n", cpu / (robots * wall), cpu, wall);
    return 0;
}

// The node of `at-once`: serves one client after another on `port` (the
// start-up's probe, then the bench's client), spinning on its socket.
int serve_at_once(uint16_t port)
{
    int listener = ::socket(AF_INET, SOCK_STREAM, 0);
    int on = 1;
    setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    sockaddr_in address = loopback_address(port);
    if (listener < 0 ||
        ::bind(listener, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0 ||
        ::listen(listener, 4) != 0)
        throw std::runtime_error("cannot listen on port " + std::to_string(port));
    constexpr size_t header_bytes = 6; // length, source, type: a word each
    const std::vector<uint8_t> pong = aseba::client::serialize_frame({ node_id, pong_event, {} });
    for (;;) {
        int client = ::accept(listener, nullptr, nullptr);
        if (client < 0)
            continue;
        setsockopt(client, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
        std::vector<uint8_t> received, answers;
        uint8_t buffer[4096];
        for (;;) {
            ssize_t count = ::recv(client, buffer, sizeof buffer, MSG_DONTWAIT);
            if (count == 0 || (count < 0 && errno != EAGAIN && errno != EWOULDBLOCK))
                break;
            if (count < 0)
                continue;
            received.insert(received.end(), buffer, buffer + count);
            size_t start = 0;
            answers.clear();
            auto word_at = [&](size_t at) {
                return static_cast<uint16_t>(received[at] | received[at + 1] << 8);
            };
            while (received.size() - start >= header_bytes &&
                   received.size() - start >= header_bytes + word_at(start)) {
                uint16_t type = word_at(start + 4);
                if (type == ping_event)
                    answers.insert(answers.end(), pong.begin(), pong.end());
                if (type == NODE_MSG_GET_VARIABLES && word_at(start) >= 6) {
                    // VARIABLES: the first address asked (the payload's
                    // second word), then as many zero words as asked (its third).
                    Frame variables{ node_id, NODE_MSG_VARIABLES, {} };
                    variables.payload.assign(2 + 2 * word_at(start + header_bytes + 4), 0);
                    variables.payload[0] = received[start + header_bytes + 2];
                    variables.payload[1] = received[start + header_bytes + 3];
                    std::vector<uint8_t> bytes = aseba::client::serialize_frame(variables);
                    answers.insert(answers.end(), bytes.begin(), bytes.end());
                }
                start += header_bytes + word_at(start);
            }
            received.erase(received.begin(), received.begin() + static_cast<long>(start));
            if (!answers.empty())
                ::send(client, answers.data(), answers.size(), MSG_NOSIGNAL);
        }
        ::close(client);
    }
}

} // namespace

int main(int argc, char **argv)
try {
    std::string mode = argc > 1 ? argv[1] : "";
    int events = argc > 2 ? std::atoi(argv[2]) : default_event_count;
    if ((mode == "emu" || mode == "reference" || mode == "at-once") && argc <= 3 &&
        events >= event_window)
        return bench_node(mode == "emu"         ? NodeKind::Ours
                          : mode == "reference" ? NodeKind::Reference
                                                : NodeKind::AtOnce,
                          events);
    if (mode == "serve-at-once" && argc == 3)
        return serve_at_once(static_cast<uint16_t>(std::atoi(argv[2])));
    if (mode == "simulator" && argc == 4)
        return bench_simulator(static_cast<unsigned>(std::atoi(argv[2])), std::atof(argv[3]));
    std::fprintf(
      stderr,
      "usage: bench-node emu|reference|at-once [EVENTS]  |  bench-node simulator ROBOTS SECONDS\n"
      "       bench-node serve-at-once PORT\n");
    return 2;
} catch (const std::exception &error) {
    std::fprintf(stderr, "bench-node: %s\n", error.what());
    return 1;
}
