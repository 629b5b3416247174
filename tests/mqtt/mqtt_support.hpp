// What the MQTT bridge's end-to-end tests need around them: Debian's
// mosquitto on a free loopback port (stopped by its pid), the bridge
// running with its log in a file, an MQTT client for the test's side, and
// the robots' variables read by name.

#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tests/console/console_support.hpp"
#include "tools/client/network.hpp"
#include "tools/mqtt/broker_client.hpp"

namespace mqtt_test
{

using Milliseconds = std::chrono::milliseconds;

// The robots' program: events trigger(ID, V) and ping(V), variables
// received and last.
std::string relay_program();
constexpr uint16_t TRIGGER = 0;
constexpr uint16_t PING = 1;

// Polls `done` every 10 ms until it is true (true) or `limit` passes.
bool eventually(const std::function<bool()> &done, Milliseconds limit = Milliseconds(10000));

// mosquitto with persistence in `folder`, on `port` (0: a free one) of the
// loopback; started by the constructor and start(), which return once it
// listens.
class Broker
{
  public:
    explicit Broker(const std::string &folder, uint16_t port = 0);
    void start();
    void stop(); // SIGTERM by pid: it saves its sessions and exits
    uint16_t port() const
    {
        return port_;
    }
    std::string url() const;

  private:
    std::string folder_;
    uint16_t port_;
    std::unique_ptr<console_test::ReferenceProgram> process_;
};

// aseba-mqtt with `arguments`, its log in `folder`/NAME.log.
class BridgeProcess
{
  public:
    BridgeProcess(const std::string &folder,
                  const std::string &name,
                  const std::vector<std::string> &arguments);
    std::string log() const;
    bool running()
    {
        return process_->running();
    }
    void stop()
    {
        process_.reset();
    }

  private:
    std::string log_path_;
    std::unique_ptr<console_test::ReferenceProgram> process_;
};

// The test's own MQTT client: what arrived, by topic, in order.
class TestClient
{
  public:
    TestClient(const Broker &broker, const std::string &name, std::vector<std::string> filters);
    bool wait_connected();
    void publish(const std::string &topic, const std::string &payload, bool retain = false);
    // Every message so far (kept), then those of `topic`.
    const std::vector<aseba::mqtt::InboundMessage> &messages();
    std::vector<std::string> payloads(const std::string &topic);

  private:
    std::unique_ptr<aseba::mqtt::BrokerClient> client_;
    std::vector<aseba::mqtt::InboundMessage> messages_;
};

// A loopback port P, free with P + 1 (epuck-emu's --robot-ports for two
// robots).
uint16_t free_port_pair();

// Sends trigger(ROBOT, VALUE) on a robot's own port (epuck-emu
// --robot-ports): only that robot hears it, no other tool of its network.
void trigger_alone(uint16_t robot_port, uint16_t robot, int16_t value);

// The robots of one network as the test sees them: variables by name,
// events heard with their source, events sent as a host.
class Robots
{
  public:
    explicit Robots(const std::string &target);
    int16_t variable(uint16_t id, const std::string &name);
    void trigger(uint16_t robot, int16_t value);
    // The sources of the pings heard so far (polls the network).
    std::vector<uint16_t> ping_sources();
    aseba::client::Network &network()
    {
        return network_;
    }

  private:
    aseba::client::Network network_;
    std::vector<uint16_t> ping_sources_;
};

} // namespace mqtt_test
