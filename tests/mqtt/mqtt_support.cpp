// Processes and clients for the MQTT bridge's end-to-end tests.

#include "mqtt_support.hpp"

#include <fstream>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>
#include <sstream>
#include <thread>

#include "tools/client/program.hpp"
#include "tools/client/variables.hpp"

namespace mqtt_test
{

using namespace console_test;
namespace client = aseba::client;

namespace
{

constexpr const char *MOSQUITTO = "/usr/sbin/mosquitto";
constexpr const char *RELAY_PROGRAM = "tests/mqtt/data/relay.aesl";

std::string read_file(const std::string &path)
{
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

} // namespace

std::string relay_program()
{
    return RELAY_PROGRAM;
}

bool eventually(const std::function<bool()> &done, Milliseconds limit)
{
    auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done()) {
        if (std::chrono::steady_clock::now() >= deadline)
            return false;
        std::this_thread::sleep_for(Milliseconds(10));
    }
    return true;
}

uint16_t free_port_pair()
{
    for (int attempt = 0; attempt < 100; attempt++) {
        uint16_t port = find_free_port();
        int fd = socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        address.sin_port = htons(uint16_t(port + 1));
        bool free =
          port < 65535 && bind(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0;
        close(fd);
        if (free)
            return port;
    }
    throw std::runtime_error("no two free loopback ports in a row");
}

void trigger_alone(uint16_t robot_port, uint16_t robot, int16_t value)
{
    client::Network network;
    network.connect("tcp:localhost;" + std::to_string(robot_port));
    network.emit(TRIGGER, { int16_t(robot), value });
}

Broker::Broker(const std::string &folder, uint16_t port)
  : folder_(folder)
  , port_(port != 0 ? port : find_free_port())
{
    start();
}

void Broker::start()
{
    // Sessions and retained messages are saved when it stops, so that a
    // restart keeps them (docs/mqtt.md: what the bridge needs of a broker).
    std::ofstream(folder_ + "/mosquitto.conf")
      << "listener " << port_ << " 127.0.0.1\n"
      << "allow_anonymous true\n"
      << "persistence true\n"
      << "persistence_location " << folder_
      << "/\n"
      // mosquitto drops QoS 1 messages beyond 1,000 queued for a subscriber
      // that is late (docs/mqtt.md); the bench's bursts of 20,000 would
      // measure that limit rather than the bridge.
      << "max_queued_messages 0\n"
      << "user root\n"; // run by root (CI), it would otherwise switch user
    process_ = std::make_unique<ReferenceProgram>(
      std::vector<std::string>{ MOSQUITTO, "-c", folder_ + "/mosquitto.conf" },
      std::vector<std::string>{},
      folder_ + "/mosquitto.log");
    if (!eventually([&] { return is_listening(port_); }, Milliseconds(5000)))
        throw std::runtime_error("mosquitto did not start: " +
                                 read_file(folder_ + "/mosquitto.log"));
}

void Broker::stop()
{
    process_.reset();
}

std::string Broker::url() const
{
    return "mqtt://127.0.0.1:" + std::to_string(port_);
}

BridgeProcess::BridgeProcess(const std::string &folder,
                             const std::string &name,
                             const std::vector<std::string> &arguments)
  : log_path_(folder + "/" + name + ".log")
{
    std::vector<std::string> command{
        program_path("aseba-mqtt"), "--name", name, "--duration", "120"
    }; // should the test die
    command.insert(command.end(), arguments.begin(), arguments.end());
    process_ = std::make_unique<ReferenceProgram>(command, std::vector<std::string>{}, log_path_);
}

std::string BridgeProcess::log() const
{
    return read_file(log_path_);
}

TestClient::TestClient(const Broker &broker,
                       const std::string &name,
                       std::vector<std::string> filters)
{
    aseba::mqtt::BrokerOptions options;
    options.address = aseba::mqtt::parse_broker_url(broker.url());
    options.client_id = "test-" + name + "-" + std::to_string(getpid());
    options.inbox_limit = 100000;
    client_ = std::make_unique<aseba::mqtt::BrokerClient>(options, [] {});
    client_->subscribe(std::move(filters), 1);
}

bool TestClient::wait_connected()
{
    return eventually([&] { return client_->connected(); }, Milliseconds(5000));
}

void TestClient::publish(const std::string &topic, const std::string &payload, bool retain)
{
    client_->publish(topic, payload, 1, retain);
}

const std::vector<aseba::mqtt::InboundMessage> &TestClient::messages()
{
    for (aseba::mqtt::InboundMessage &message : client_->take_messages())
        messages_.push_back(std::move(message));
    return messages_;
}

std::vector<std::string> TestClient::payloads(const std::string &topic)
{
    std::vector<std::string> found;
    for (const aseba::mqtt::InboundMessage &message : messages())
        if (message.topic == topic)
            found.push_back(message.payload);
    return found;
}

Robots::Robots(const std::string &target)
{
    network_.set_listener([this](const client::ReceivedFrame &frame) {
        if (frame.message && std::holds_alternative<client::UserEvent>(*frame.message) &&
            std::get<client::UserEvent>(*frame.message).id == PING)
            ping_sources_.push_back(frame.frame.source);
    });
    network_.connect(target);
    network_.discover();
}

int16_t Robots::variable(uint16_t id, const std::string &name)
{
    for (client::NodeKey key : network_.select(std::to_string(id))) {
        client::ProgramFile file = client::read_program_file(RELAY_PROGRAM);
        client::CompiledProgram program =
          client::compile_program(file, network_.node(key).description, id);
        client::VariableSlice slice =
          client::resolve_variable(client::parse_variable_reference(name),
                                   client::variable_map(network_.node(key).description, &program));
        return network_.read_variables(key, slice.address, 1).at(0);
    }
    throw std::runtime_error("no robot " + std::to_string(id));
}

void Robots::trigger(uint16_t robot, int16_t value)
{
    network_.emit(TRIGGER, { int16_t(robot), value });
}

std::vector<uint16_t> Robots::ping_sources()
{
    network_.poll(Milliseconds(0));
    return ping_sources_;
}

} // namespace mqtt_test
