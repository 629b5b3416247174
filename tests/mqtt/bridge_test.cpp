// aseba-mqtt end to end: Debian's mosquitto and epuck-emu on free loopback
// ports, the robots running tests/mqtt/data/relay.aesl (trigger(ID, V) makes
// robot ID emit ping(V); every robot counts the pings it gets). What a test
// expects comes from docs/mqtt.md (topics, payloads) and from the robots'
// program, read back from the robots' memory.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "mqtt_support.hpp"

namespace
{

using namespace mqtt_test;
using console_test::Emulator;
using console_test::ScratchFolder;
using nlohmann::json;

// A bridge is ready when the broker holds the described presence of its nodes.
bool nodes_published(TestClient &watcher, const std::string &network, std::vector<int> ids)
{
    return eventually([&] {
        for (int id : ids) {
            std::vector<std::string> payloads =
              watcher.payloads("aseba/network/" + network + "/node/" + std::to_string(id));
            if (payloads.empty() || payloads.back().empty() ||
                !json::parse(payloads.back()).value("described", false))
                return false;
        }
        return true;
    });
}

std::string file_text(const std::string &path)
{
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

bool log_has(const BridgeProcess &bridge, const std::string &text)
{
    return eventually([&] { return bridge.log().find(text) != std::string::npos; },
                      Milliseconds(5000));
}

TEST(MqttBridge, ReadOnlyPublishesEventsAndPresenceAndRefusesCommands)
{
    ScratchFolder folder;
    Broker broker(folder.path());
    Emulator emulator(2, { "--load", relay_program() });
    BridgeProcess bridge(
      folder.path(), "a", { "-t", emulator.target(), "-b", broker.url(), "-p", relay_program() });
    TestClient watcher(broker, "watcher", { "aseba/#" });
    ASSERT_TRUE(watcher.wait_connected());
    ASSERT_TRUE(nodes_published(watcher, "a", { 1, 2 })) << bridge.log();
    json presence = json::parse(watcher.payloads("aseba/network/a/node/1").back());
    EXPECT_EQ(presence["name"], "e-puck");
    EXPECT_EQ(presence["protocol"], 5);
    EXPECT_EQ(presence["bytecode_size"], 1024);
    ASSERT_TRUE(eventually([&] { return !watcher.payloads("aseba/bridge/a").empty(); }));
    EXPECT_EQ(json::parse(watcher.payloads("aseba/bridge/a").back())["online"], true);

    Robots robots(emulator.target());
    robots.trigger(1, 7);
    ASSERT_TRUE(eventually([&] { return !watcher.payloads("aseba/event/ping").empty(); }))
      << bridge.log();
    json ping = json::parse(watcher.payloads("aseba/event/ping").front());
    EXPECT_EQ(ping["args"], json::array({ 7 }));
    EXPECT_EQ(ping["network"], "a");
    EXPECT_EQ(ping["node"], 1);
    EXPECT_EQ(ping["node_name"], "e-puck");
    // The test's own trigger, from a host tool (id 0) on the network.
    ASSERT_TRUE(eventually([&] { return !watcher.payloads("aseba/event/trigger").empty(); }));
    json trigger = json::parse(watcher.payloads("aseba/event/trigger").front());
    EXPECT_EQ(trigger["args"], json::array({ 1, 7 }));
    EXPECT_EQ(trigger["node"], 0);

    // Read-only: events from the broker are not delivered, commands refused.
    watcher.publish("aseba/event/ping", "[5]");
    watcher.publish("aseba/network/a/node/1/command", R"({"command":"stop","request":3})");
    ASSERT_TRUE(
      eventually([&] { return !watcher.payloads("aseba/network/a/node/1/reply").empty(); }));
    json reply = json::parse(watcher.payloads("aseba/network/a/node/1/reply").front());
    EXPECT_EQ(reply["ok"], false);
    EXPECT_NE(reply["error"].get<std::string>().find("read-only"), std::string::npos);
    EXPECT_EQ(reply["command"], "stop"); // echoed, as docs/mqtt.md says every reply is
    EXPECT_EQ(reply["request"], 3);
    EXPECT_TRUE(robots.network().execution_state({ 0, 1 }).running());
    EXPECT_EQ(robots.variable(1, "received"), 0); // its own ping does not come back
    EXPECT_EQ(robots.variable(2, "received"), 1); // robot 1's, on the network
    EXPECT_EQ(robots.variable(2, "last"), 7);
    EXPECT_TRUE(log_has(bridge, "refused: read-only bridge"));
}

TEST(MqttBridge, DeliversEventsAndDropsBadInput)
{
    ScratchFolder folder;
    Broker broker(folder.path());
    Emulator emulator(1, { "--load", relay_program() });
    BridgeProcess bridge(folder.path(),
                         "a",
                         { "-t",
                           emulator.target(),
                           "-b",
                           broker.url(),
                           "-p",
                           relay_program(),
                           "--accept-events",
                           "--max-event-rate",
                           "200" });
    TestClient watcher(broker, "watcher", { "aseba/network/#" });
    ASSERT_TRUE(watcher.wait_connected());
    ASSERT_TRUE(nodes_published(watcher, "a", { 1 })) << bridge.log();
    Robots robots(emulator.target());

    watcher.publish("aseba/event/ping", R"({"args":[5]})");
    ASSERT_TRUE(eventually([&] { return robots.variable(1, "last") == 5; })) << bridge.log();

    const std::pair<std::string, std::string> bad[] = {
        { "aseba/event/ping", "not json" },
        { "aseba/event/ping", R"({"args":"x"})" },
        { "aseba/event/ping", "[1,2]" },
        { "aseba/event/ping", json(std::vector<int>(40, 1)).dump() },
        { "aseba/event/ping", "[70000]" },
        { "aseba/event/ping", "[1.5]" },
        { "aseba/event/ping", std::string(100, '[') + std::string(100, ']') },
        { "aseba/event/nosuch", "[1]" },
    };
    for (const auto &[topic, payload] : bad)
        watcher.publish(topic, payload);
    watcher.publish("aseba/event/ping", "[9]");
    ASSERT_TRUE(eventually([&] { return robots.variable(1, "last") == 9; })) << bridge.log();
    EXPECT_EQ(robots.variable(1, "received"), 2); // 5 and 9, nothing between
    for (const char *line : { "the payload is not JSON",
                              "\"args\" must be an array",
                              "takes 1 arguments, not 2",
                              "more than the 32 the robots take",
                              "outside -32768..32767",
                              "is not an integer",
                              "nests arrays",
                              "no event 'nosuch'" })
        EXPECT_TRUE(log_has(bridge, line)) << line << "\n" << bridge.log();

    // A flood: dropped beyond the rate, logged, and the robot keeps running.
    for (int i = 0; i < 3000; i++)
        watcher.publish("aseba/event/ping", "[1]");
    EXPECT_TRUE(log_has(bridge, "more than 200 events per second")) << bridge.log();
    EXPECT_TRUE(eventually([&] {
        watcher.publish("aseba/event/ping", "[11]");
        return robots.variable(1, "last") == 11;
    }));
    EXPECT_TRUE(robots.network().execution_state({ 0, 1 }).running());
    EXPECT_TRUE(bridge.running());
    EXPECT_LT(robots.variable(1, "received"), 3000);
}

// Two networks, each with its bridge, on one broker: one swarm.
struct Joined {
    ScratchFolder folder;
    Broker broker{ folder.path() };
    // Each robot also on a port of its own, where a trigger reaches it alone
    // (a trigger on the network would cross to the other network too).
    uint16_t robot_ports_a = free_port_pair();
    uint16_t robot_ports_b = free_port_pair();
    Emulator emulator_a;
    Emulator emulator_b;
    std::unique_ptr<BridgeProcess> bridge_a;
    std::unique_ptr<BridgeProcess> bridge_b;
    TestClient watcher{ broker, "watcher", { "aseba/network/#", "aseba/bridge/#" } };

    Joined(unsigned robots_a, unsigned robots_b)
      : emulator_a(robots_a,
                   { "--load", relay_program(), "--robot-ports", std::to_string(robot_ports_a) })
      , emulator_b(robots_b,
                   { "--load", relay_program(), "--robot-ports", std::to_string(robot_ports_b) })
    {
        bridge_a = start("a", emulator_a);
        bridge_b = start("b", emulator_b);
    }

    std::unique_ptr<BridgeProcess> start(const std::string &name, const Emulator &emulator)
    {
        return std::make_unique<BridgeProcess>(folder.path(),
                                               name,
                                               std::vector<std::string>{ "-t",
                                                                         emulator.target(),
                                                                         "-b",
                                                                         broker.url(),
                                                                         "-p",
                                                                         relay_program(),
                                                                         "--accept-events" });
    }
};

TEST(MqttBridge, TwoNetworksJoinedWithoutLoopsAndWithRemappedIds)
{
    Joined joined(2, 1);
    ASSERT_TRUE(joined.watcher.wait_connected());
    ASSERT_TRUE(nodes_published(joined.watcher, "a", { 1, 2 })) << joined.bridge_a->log();
    ASSERT_TRUE(nodes_published(joined.watcher, "b", { 1 })) << joined.bridge_b->log();
    Robots a(joined.emulator_a.target());
    Robots b(joined.emulator_b.target());

    // Robot a1 emits: robot b1 hears it, from an id that is not its own.
    trigger_alone(joined.robot_ports_a, 1, 7);
    ASSERT_TRUE(eventually([&] { return b.variable(1, "last") == 7; })) << joined.bridge_b->log();
    trigger_alone(joined.robot_ports_a + 1, 2, 8);
    ASSERT_TRUE(eventually([&] { return b.variable(1, "last") == 8; }));
    std::vector<uint16_t> sources = b.ping_sources();
    ASSERT_EQ(sources.size(), 2u);
    EXPECT_NE(sources[0], 1); // a1 clashes with b1: remapped
    EXPECT_NE(sources[1], 1);
    EXPECT_NE(sources[0], sources[1]);
    EXPECT_NE(sources[0], 0);

    // And back: robot b1 emits, both robots of a hear it, from a free id.
    trigger_alone(joined.robot_ports_b, 1, 9);
    ASSERT_TRUE(
      eventually([&] { return a.variable(1, "last") == 9 && a.variable(2, "last") == 9; }))
      << joined.bridge_a->log();
    std::vector<uint16_t> sources_a = a.ping_sources();
    ASSERT_FALSE(sources_a.empty());
    EXPECT_TRUE(sources_a.back() != 1 && sources_a.back() != 2 && sources_a.back() != 0)
      << sources_a.back();

    // A last event behind the others: then every count is exact.
    trigger_alone(joined.robot_ports_a, 1, 10);
    ASSERT_TRUE(eventually([&] { return b.variable(1, "last") == 10; }));
    EXPECT_EQ(b.variable(1, "received"), 3); // 7, 8, 10
    EXPECT_EQ(a.variable(1, "received"), 2); // a2's 8, b1's 9
    EXPECT_EQ(a.variable(2, "received"), 3); // a1's 7, b1's 9, a1's 10
}

TEST(MqttBridge, BrokerRestartLosesNoEvent)
{
    Joined joined(1, 1);
    ASSERT_TRUE(joined.watcher.wait_connected());
    ASSERT_TRUE(nodes_published(joined.watcher, "a", { 1 }));
    ASSERT_TRUE(nodes_published(joined.watcher, "b", { 1 }));
    Robots a(joined.emulator_a.target());
    Robots b(joined.emulator_b.target());
    trigger_alone(joined.robot_ports_a, 1, 1);
    ASSERT_TRUE(eventually([&] { return b.variable(1, "last") == 1; }));

    joined.broker.stop();
    ASSERT_TRUE(log_has(*joined.bridge_a, "unreachable")) << joined.bridge_a->log();
    for (int16_t value : { 2, 3, 4 })
        trigger_alone(joined.robot_ports_a, 1, value);
    // Robot a1 emitted every ping (so the bridge heard them) before the
    // broker comes back.
    ASSERT_TRUE(eventually([&] { return a.ping_sources().size() == 4; }));
    joined.broker.start();
    ASSERT_TRUE(eventually([&] { return b.variable(1, "last") == 4; }, Milliseconds(15000)))
      << joined.bridge_a->log() << joined.bridge_b->log();
    EXPECT_EQ(b.variable(1, "received"), 4); // 1, 2, 3, 4: none lost, none twice

    // The retained state is there for a newcomer.
    TestClient newcomer(joined.broker, "newcomer", { "aseba/#" });
    ASSERT_TRUE(newcomer.wait_connected());
    EXPECT_TRUE(nodes_published(newcomer, "a", { 1 }));
    ASSERT_TRUE(eventually([&] { return !newcomer.payloads("aseba/bridge/a").empty(); }));
    EXPECT_EQ(json::parse(newcomer.payloads("aseba/bridge/a").back())["online"], true);
}

TEST(MqttBridge, NetworkThatGoesAndComesBack)
{
    ScratchFolder folder;
    Broker broker(folder.path());
    auto emulator =
      std::make_unique<Emulator>(1, std::vector<std::string>{ "--load", relay_program() });
    uint16_t port = emulator->port();
    BridgeProcess bridge(
      folder.path(), "a", { "-t", emulator->target(), "-b", broker.url(), "-p", relay_program() });
    TestClient watcher(broker, "watcher", { "aseba/#" });
    ASSERT_TRUE(watcher.wait_connected());
    ASSERT_TRUE(nodes_published(watcher, "a", { 1 }));

    emulator->kill_now();
    // The node is gone: its retained presence is emptied.
    ASSERT_TRUE(eventually([&] {
        std::vector<std::string> payloads = watcher.payloads("aseba/network/a/node/1");
        return payloads.back().empty();
    }))
      << bridge.log();
    emulator =
      std::make_unique<Emulator>(1, std::vector<std::string>{ "--load", relay_program() }, port);
    ASSERT_TRUE(nodes_published(watcher, "a", { 1 })) << bridge.log();
    Robots robots(emulator->target());
    robots.trigger(1, 5);
    EXPECT_TRUE(eventually([&] {
        for (const std::string &payload : watcher.payloads("aseba/event/ping"))
            if (json::parse(payload)["args"] == json::array({ 5 }))
                return true;
        return false;
    }));
    EXPECT_TRUE(bridge.running());
}

TEST(MqttBridge, RunsCommandsWhenAllowed)
{
    ScratchFolder folder;
    Broker broker(folder.path());
    Emulator emulator(1, { "--load", relay_program() });
    BridgeProcess bridge(
      folder.path(),
      "a",
      { "-t", emulator.target(), "-b", broker.url(), "-p", relay_program(), "--accept-commands" });
    TestClient watcher(broker, "watcher", { "aseba/network/#" });
    ASSERT_TRUE(watcher.wait_connected());
    ASSERT_TRUE(nodes_published(watcher, "a", { 1 }));
    Robots robots(emulator.target());
    const std::string command = "aseba/network/a/node/1/command";
    const std::string reply_topic = "aseba/network/a/node/1/reply";
    auto reply = [&](size_t index) {
        EXPECT_TRUE(eventually([&] { return watcher.payloads(reply_topic).size() > index; }))
          << bridge.log();
        return json::parse(watcher.payloads(reply_topic).at(index));
    };

    watcher.publish(command, R"({"command":"stop","request":{"id":1}})");
    json stopped = reply(0);
    EXPECT_EQ(stopped["ok"], true);
    EXPECT_EQ(stopped["state"], "stopped");
    EXPECT_EQ(stopped["request"], json({ { "id", 1 } }));
    EXPECT_TRUE(robots.network().execution_state({ 0, 1 }).stopped());

    watcher.publish(command, R"({"command":"run"})");
    EXPECT_EQ(reply(1)["state"], "running");

    // A new program: the same variables, another handler.
    watcher.publish(
      command,
      json(
        { { "command", "load" },
          { "program", "var received = 0\nvar last = 0\nonevent ping\nlast = args[0] + 100\n" } })
        .dump());
    json loaded = reply(2);
    EXPECT_EQ(loaded["ok"], true) << loaded.dump();
    robots.network().emit(PING, { 5 });
    EXPECT_TRUE(eventually([&] { return robots.variable(1, "last") == 105; }));

    watcher.publish(command, R"({"command":"load","program":"onevent ping\nnosuch = 1\n"})");
    json failed = reply(3);
    EXPECT_EQ(failed["ok"], false);
    EXPECT_FALSE(failed["error"].get<std::string>().empty());
    watcher.publish(command, R"({"command":"fly"})");
    EXPECT_NE(reply(4)["error"].get<std::string>().find("unknown command"), std::string::npos);
    watcher.publish("aseba/network/a/node/9/command", R"({"command":"run"})");
    EXPECT_TRUE(
      eventually([&] { return !watcher.payloads("aseba/network/a/node/9/reply").empty(); }));
    EXPECT_NE(watcher.payloads("aseba/network/a/node/9/reply")[0].find("no node 9"),
              std::string::npos);
}

// examples/mqtt/record_events.py, with Debian's paho (an independent MQTT
// client): its CSV rows, and its event delivered to the robots.
TEST(MqttBridge, PythonExampleRecordsAndSends)
{
    ScratchFolder folder;
    Broker broker(folder.path());
    Emulator emulator(1, { "--load", relay_program() });
    BridgeProcess bridge(
      folder.path(),
      "a",
      { "-t", emulator.target(), "-b", broker.url(), "-p", relay_program(), "--accept-events" });
    TestClient watcher(broker, "watcher", { "aseba/network/#" });
    ASSERT_TRUE(watcher.wait_connected());
    ASSERT_TRUE(nodes_published(watcher, "a", { 1 }));
    std::string csv = folder.path() + "/events.csv";
    std::string log = folder.path() + "/example.log";
    console_test::ReferenceProgram example({ "/usr/bin/python3",
                                             "examples/mqtt/record_events.py",
                                             "--broker",
                                             "127.0.0.1:" + std::to_string(broker.port()),
                                             "--csv",
                                             csv,
                                             "--count",
                                             "2",
                                             "--duration",
                                             "20",
                                             "--send",
                                             "ping",
                                             "42" },
                                           {},
                                           log);
    ASSERT_TRUE(eventually([&] { return file_text(log).find("recording") != std::string::npos; }))
      << file_text(log);
    Robots robots(emulator.target());
    robots.trigger(1, 7); // the trigger, then robot 1's ping
    ASSERT_TRUE(eventually([&] { return !example.running(); }, Milliseconds(20000)))
      << file_text(log);
    EXPECT_TRUE(eventually([&] { return robots.variable(1, "last") == 42; })) << file_text(log);
    std::vector<std::string> rows = console_test::lines_of(file_text(csv));
    ASSERT_EQ(rows.size(), 3u) << file_text(csv);
    EXPECT_EQ(rows[0], "received,time_ms,network,node,node_name,event,args");
    // received,time_ms, then the rest is known.
    auto tail = [](const std::string &row) {
        return row.substr(row.find(',', row.find(',') + 1) + 1);
    };
    EXPECT_EQ(tail(rows[1]), "a,0,,trigger,1 7");
    EXPECT_EQ(tail(rows[2]), "a,1,e-puck,ping,7");
}

} // namespace
