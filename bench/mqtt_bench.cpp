// bench-mqtt: the MQTT bridge's figures for `make bench`, on the loopback,
// with Debian's mosquitto and epuck-emu started on free ports.
//
//   bench-mqtt latency S      a robot of network a emits tick(n) every 20 ms
//                             (bench/mqtt_ticker.aesl); bridges a and b join
//                             the networks; a robot of network b answers
//                             tock(n) (bench/mqtt_echo.aesl). The time from
//                             tick(n) heard on a to tock(n) heard on b, for S
//                             seconds: prints "MEDIAN_MS P99_MS SAMPLES".
//   bench-mqtt throughput N   one bridge, in front of a network of our own
//                             that sends N robot events as fast as the bridge
//                             reads them, then receives N events published on
//                             the broker: prints "OUT_PER_SECOND IN_PER_SECOND
//                             PUBLISHED DELIVERED".

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "tests/mqtt/mqtt_support.hpp"

namespace
{

using namespace mqtt_test;
using console_test::Emulator;
using console_test::ScratchFolder;
namespace client = aseba::client;
using Clock = std::chrono::steady_clock;

constexpr uint16_t TICK = 0;
constexpr uint16_t TOCK = 1;

double milliseconds(Clock::duration duration)
{
    return std::chrono::duration<double, std::milli>(duration).count();
}

// The id of event `id` arriving at `network`, with its first argument and time.
void on_events(client::Network &network, uint16_t id, std::map<int16_t, Clock::time_point> &times)
{
    network.set_listener([&times, id](const client::ReceivedFrame &frame) {
        if (!frame.message || !std::holds_alternative<client::UserEvent>(*frame.message))
            return;
        const auto &event = std::get<client::UserEvent>(*frame.message);
        if (event.id == id && !event.arguments.empty())
            times.try_emplace(event.arguments[0], frame.time);
    });
}

int latency(double seconds)
{
    ScratchFolder folder;
    Broker broker(folder.path());
    Emulator a(1, { "--load", "bench/mqtt_ticker.aesl" });
    Emulator b(1, { "--load", "bench/mqtt_echo.aesl" });
    BridgeProcess bridge_a(
      folder.path(),
      "a",
      { "-t", a.target(), "-b", broker.url(), "--accept-events", "-p", "bench/mqtt_ticker.aesl" });
    BridgeProcess bridge_b(
      folder.path(),
      "b",
      { "-t", b.target(), "-b", broker.url(), "--accept-events", "-p", "bench/mqtt_echo.aesl" });
    std::map<int16_t, Clock::time_point> ticks, tocks;
    client::Network network_a, network_b;
    on_events(network_a, TICK, ticks);
    on_events(network_b, TOCK, tocks);
    network_a.connect(a.target());
    network_b.connect(b.target());
    // Warm up: until the first tock comes back.
    bool warm = false;
    auto give_up = Clock::now() + std::chrono::seconds(20);
    while (!warm && Clock::now() < give_up) {
        network_a.poll(client::Milliseconds(1));
        network_b.poll(client::Milliseconds(1));
        warm = !tocks.empty();
    }
    if (!warm) {
        std::cerr << "bench-mqtt: no tock came back\n" << bridge_a.log() << bridge_b.log();
        return 1;
    }
    int16_t first = int16_t(tocks.rbegin()->first + 1);
    auto end = Clock::now() +
               std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    while (Clock::now() < end) {
        network_a.poll(client::Milliseconds(1));
        network_b.poll(client::Milliseconds(1));
    }
    // The last ticks' answers.
    auto drain = Clock::now() + std::chrono::seconds(1);
    while (Clock::now() < drain) {
        network_a.poll(client::Milliseconds(1));
        network_b.poll(client::Milliseconds(1));
    }
    std::vector<double> latencies;
    for (const auto &[n, tick] : ticks) {
        auto tock = tocks.find(n);
        if (n >= first && tock != tocks.end())
            latencies.push_back(milliseconds(tock->second - tick));
    }
    if (latencies.empty()) {
        std::cerr << "bench-mqtt: no samples\n";
        return 1;
    }
    std::sort(latencies.begin(), latencies.end());
    auto at = [&](double fraction) {
        return latencies[std::min(latencies.size() - 1, size_t(fraction * latencies.size()))];
    };
    std::printf("%.2f %.2f %zu\n", at(0.5), at(0.99), latencies.size());
    return 0;
}

// A network of our own on a loopback port, in place of epuck-emu (whose
// robots take events at their own simulated pace): it accepts the bridge,
// writes frames as fast as the bridge reads them, and counts user events.
class FakeNetwork
{
  public:
    FakeNetwork()
    {
        listener_ = socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        socklen_t length = sizeof address;
        if (bind(listener_, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0 ||
            listen(listener_, 1) != 0 ||
            getsockname(listener_, reinterpret_cast<sockaddr *>(&address), &length) != 0)
            throw std::runtime_error("bench-mqtt: cannot listen");
        port_ = ntohs(address.sin_port);
    }
    ~FakeNetwork()
    {
        if (connection_ >= 0)
            close(connection_);
        close(listener_);
    }
    std::string target() const
    {
        return "tcp:127.0.0.1;" + std::to_string(port_);
    }
    void accept_bridge()
    {
        connection_ = accept(listener_, nullptr, nullptr);
        int one = 1;
        setsockopt(connection_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    }
    void send(const std::vector<uint8_t> &bytes)
    {
        for (size_t sent = 0; sent < bytes.size();) {
            ssize_t count = write(connection_, bytes.data() + sent, bytes.size() - sent);
            if (count <= 0)
                throw std::runtime_error("bench-mqtt: the bridge went away");
            sent += size_t(count);
        }
    }
    // Reads what the bridge sent (waiting up to `timeout_ms`); returns the
    // user events of type `id` among it.
    size_t receive(uint16_t id, int timeout_ms)
    {
        pollfd waiting{ connection_, POLLIN, 0 };
        if (poll(&waiting, 1, timeout_ms) <= 0)
            return 0;
        uint8_t buffer[65536];
        ssize_t count = read(connection_, buffer, sizeof buffer);
        if (count <= 0)
            throw std::runtime_error("bench-mqtt: the bridge went away");
        pending_.insert(pending_.end(), buffer, buffer + count);
        size_t events = 0;
        // Frames: length (payload bytes), source, type, all little-endian.
        while (pending_.size() >= 6) {
            size_t payload = size_t(pending_[0] | (pending_[1] << 8));
            if (pending_.size() < 6 + payload)
                break;
            uint16_t type = uint16_t(pending_[4] | (pending_[5] << 8));
            if (type == id)
                events++;
            pending_.erase(pending_.begin(), pending_.begin() + long(6 + payload));
        }
        return events;
    }

  private:
    int listener_ = -1;
    int connection_ = -1;
    uint16_t port_ = 0;
    std::vector<uint8_t> pending_;
};

double since(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

int throughput(unsigned count)
{
    ScratchFolder folder;
    Broker broker(folder.path());
    FakeNetwork network;
    BridgeProcess bridge(folder.path(),
                         "a",
                         { "-t",
                           network.target(),
                           "-b",
                           broker.url(),
                           "--accept-events",
                           "--max-event-rate",
                           "1000000" });
    network.accept_bridge();
    TestClient subscriber(broker, "counter", { "aseba/event/7", "aseba/bridge/a" });
    if (!subscriber.wait_connected() ||
        !eventually([&] { return !subscriber.payloads("aseba/bridge/a").empty(); })) {
        std::cerr << "bench-mqtt: the bridge did not start\n" << bridge.log();
        return 1;
    }
    // Out: robot events (from node 1) to the broker.
    auto start = Clock::now();
    for (unsigned i = 0; i < count; i++) {
        network.send(
          client::serialize_frame(client::encode(client::UserEvent{ 7, { int16_t(i) } }, 1)));
        network.receive(8, 0);
    }
    size_t published = 0;
    eventually(
      [&] {
          network.receive(8, 0);
          published = subscriber.payloads("aseba/event/7").size();
          return published >= count;
      },
      Milliseconds(60000));
    double out_rate = published / since(start);
    // In: events published on the broker to the network.
    TestClient publisher(broker, "publisher", {});
    publisher.wait_connected();
    start = Clock::now();
    size_t delivered = 0;
    for (unsigned i = 0; i < count; i++) {
        publisher.publish("aseba/event/8", "[" + std::to_string(i) + "]");
        delivered += network.receive(8, 0);
    }
    auto give_up = Clock::now() + std::chrono::seconds(60);
    while (delivered < count && Clock::now() < give_up)
        delivered += network.receive(8, 10);
    double in_rate = delivered / since(start);
    std::printf("%.0f %.0f %zu %zu\n", out_rate, in_rate, published, delivered);
    if (published != count || delivered != count)
        std::cerr << "bench-mqtt: events lost\n" << bridge.log();
    return published == count && delivered == count ? 0 : 1;
}

} // namespace

int main(int argc, char **argv)
{
    std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "latency" && argc == 3)
        return latency(std::atof(argv[2]));
    if (mode == "throughput" && argc == 3)
        return throughput(unsigned(std::atoi(argv[2])));
    std::cerr << "usage: bench-mqtt latency SECONDS | throughput EVENTS\n";
    return 2;
}
