// The client library's network model against epuck-emu: discovery and
// description, variables read in split requests, execution control, and a
// silent target that must time out instead of hanging.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <netinet/in.h>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>

#include "console_support.hpp"
#include "tools/client/network.hpp"
#include "tools/compiler/target_presets.hpp"

using namespace aseba;
using namespace aseba::client;
using console_test::Emulator;

namespace
{

// The e-puck as robots/epuck/epuck_description.h describes it, through the
// compiler's preset (a path that does not go through the wire).
const TargetDescription &expected_epuck()
{
    static const TargetDescription description = epuck_target();
    return description;
}

} // namespace

TEST(NetworkModel, DiscoversAndDescribesEveryRobot)
{
    Emulator emulator(2);
    Network network;
    network.connect(emulator.target());
    network.discover();
    std::vector<NodeKey> keys = network.node_keys();
    ASSERT_EQ(keys.size(), 2u);
    for (uint16_t id = 1; id <= 2; id++) {
        const Node &node = network.node(keys[id - 1]);
        EXPECT_EQ(node.key.id, id);
        ASSERT_TRUE(node.described);
        EXPECT_EQ(node.protocol_version, 5);
        const TargetDescription &description = node.description;
        EXPECT_EQ(description.name, "e-puck");
        EXPECT_EQ(description.bytecode_size, expected_epuck().bytecode_size);
        EXPECT_EQ(description.stack_size, expected_epuck().stack_size);
        ASSERT_EQ(description.named_variables.size(), expected_epuck().named_variables.size());
        for (size_t i = 0; i < description.named_variables.size(); i++) {
            EXPECT_EQ(description.named_variables[i].name,
                      expected_epuck().named_variables[i].name);
            EXPECT_EQ(description.named_variables[i].size,
                      expected_epuck().named_variables[i].size);
        }
        ASSERT_EQ(description.local_events.size(), expected_epuck().local_events.size());
        EXPECT_EQ(description.local_events[0].name, "ir_sensors");
        ASSERT_EQ(description.native_functions.size(), expected_epuck().native_functions.size());
        for (size_t i = 0; i < description.native_functions.size(); i++)
            EXPECT_EQ(description.native_functions[i].name,
                      expected_epuck().native_functions[i].name);
    }
    EXPECT_EQ(network.select("2").size(), 1u);
    EXPECT_EQ(network.select("e-puck").size(), 2u);
    EXPECT_EQ(network.select("all").size(), 2u);
    EXPECT_THROW(network.select("7"), NetworkError);
    EXPECT_EQ(network.malformed_frames(), 0u);
}

// All the variable memory at once needs two GET_VARIABLES (257 words max);
// the values written before come back at their addresses.
TEST(NetworkModel, ReadsAndWritesBeyondOneMessage)
{
    Emulator emulator(1);
    Network network;
    network.connect(emulator.target());
    network.discover();
    NodeKey key = network.select("1").at(0);
    uint16_t size = network.node(key).description.variables_size;
    ASSERT_GT(size, MAX_VARIABLES_WORDS);

    // The free memory after the named variables (no program is loaded, so
    // nothing else writes there).
    uint16_t free_start = 0;
    for (const NamedVariable &variable : network.node(key).description.named_variables)
        free_start = uint16_t(free_start + variable.size);
    std::vector<int16_t> pattern(size - free_start);
    for (size_t i = 0; i < pattern.size(); i++)
        pattern[i] = int16_t(1000 - 7 * int(i));
    network.write_variables(key, free_start, pattern);

    std::vector<int16_t> all = network.read_variables(key, 0, size);
    ASSERT_EQ(all.size(), size);
    EXPECT_EQ(all[0], 1); // the id variable holds the node id
    for (size_t i = 0; i < pattern.size(); i++)
        EXPECT_EQ(all[free_start + i], pattern[i]) << "word " << free_start + i;
    EXPECT_THROW(network.read_variables(key, size - 1, 2), NetworkError);
}

TEST(NetworkModel, ExecutionControlAnswers)
{
    Emulator emulator(1);
    Network network;
    network.connect(emulator.target());
    network.discover();
    NodeKey key = network.select("all").at(0);
    // Without a program the node idles: stop leaves it stopped, run running
    // (bytecode.md §6.4: STOP answers flags STEP_BY_STEP).
    ExecutionState stopped = network.stop(key);
    EXPECT_EQ(stopped.flags, FLAG_STEP_BY_STEP);
    EXPECT_TRUE(stopped.stopped());
    EXPECT_TRUE(network.run(key).running());
    EXPECT_TRUE(network.pause(key).flags & FLAG_STEP_BY_STEP);
    EXPECT_TRUE(network.run(key).running());
}

// A peer that accepts the connection and never answers: discovery finds
// nothing and a command fails within the time limit.
TEST(NetworkModel, SilentTargetTimesOut)
{
    int listener = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    ASSERT_EQ(bind(listener, reinterpret_cast<sockaddr *>(&address), sizeof address), 0);
    ASSERT_EQ(listen(listener, 1), 0);
    ASSERT_EQ(getsockname(listener, reinterpret_cast<sockaddr *>(&address), &length), 0);

    Network network(Milliseconds(300));
    network.connect("tcp:127.0.0.1;" + std::to_string(ntohs(address.sin_port)));
    auto start = Clock::now();
    network.discover();
    auto waited = Clock::now() - start;
    EXPECT_TRUE(network.node_keys().empty());
    EXPECT_GE(waited, Milliseconds(290));
    EXPECT_LT(waited, Milliseconds(2000));
    EXPECT_THROW(network.select("all"), NetworkError);
    close(listener);
}

namespace
{

// A scripted node: it answers LIST_NODES and GET_NODE_DESCRIPTION like a
// protocol-5 node (id 5, "fake"), first sending a malformed frame, and also
// speaks for a node 6 of protocol version 6 that hosts must ignore.
std::vector<Frame> fake_node_answer(const Frame &frame)
{
    std::vector<Frame> replies;
    auto send = [&](const Message &message, uint16_t source) {
        replies.push_back(encode(message, source));
    };
    Message message = decode(frame);
    if (std::holds_alternative<ListNodes>(message)) {
        // An odd-length user event: malformed, to be dropped.
        replies.push_back(Frame{ 5, 1, { 1, 2, 3 } });
        send(NodePresent{ 5 }, 5);
        send(NodePresent{ 6 }, 6);
    } else if (const auto *get = std::get_if<GetNodeDescription>(&message)) {
        uint16_t version = get->dest == 6 ? 6 : 5;
        send(Description{ "fake", version, 100, 16, 40, 2, 1, 1 }, get->dest);
        send(NamedVariableDescription{ { "id", 1 } }, get->dest);
        send(NamedVariableDescription{ { "table", 20 } }, get->dest);
        send(LocalEventDescription{ { "tick", "timer" } }, get->dest);
        send(NativeFunctionDescription{ { "f", "", { { "x", 1 } } } }, get->dest);
    } else if (const auto *request = std::get_if<GetVariables>(&message)) {
        // Answers in two parts, the second first (hosts merge by start).
        uint16_t half = uint16_t(request->length / 2);
        std::vector<int16_t> high, low;
        for (uint16_t i = 0; i < request->length; i++)
            (i < half ? low : high).push_back(int16_t(request->start + i));
        send(Variables{ uint16_t(request->start + half), high }, 5);
        send(Variables{ request->start, low }, 5);
    }
    return replies;
}

} // namespace

TEST(NetworkModel, AssemblesDescriptionsAndSurvivesBadFrames)
{
    console_test::ScriptedPeer fake(fake_node_answer);
    Network network;
    network.connect(fake.target());
    std::vector<std::string> errors;
    network.set_listener([&](const ReceivedFrame &frame) {
        if (!frame.message)
            errors.push_back(frame.error);
    });
    network.discover();
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("odd number of bytes"), std::string::npos) << errors[0];
    EXPECT_EQ(network.malformed_frames(), 1u);

    std::vector<NodeKey> selected = network.select("all");
    ASSERT_EQ(selected.size(), 1u); // node 6 speaks protocol 6: ignored
    EXPECT_EQ(selected[0].id, 5);
    const Node &node = network.node(selected[0]);
    EXPECT_EQ(node.description.name, "fake");
    EXPECT_EQ(node.description.variables_size, 40);
    ASSERT_EQ(node.description.named_variables.size(), 2u);
    EXPECT_EQ(node.description.named_variables[1].name, "table");
    EXPECT_EQ(node.description.named_variables[1].size, 20);
    EXPECT_EQ(node.description.local_events.at(0).name, "tick");
    EXPECT_EQ(node.description.native_functions.at(0).parameters.at(0).name, "x");
    EXPECT_FALSE(network.node({ 0, 6 }).compatible);

    // The fake answers each read in two messages, the later words first.
    std::vector<int16_t> values = network.read_variables(selected[0], 1, 20);
    for (size_t i = 0; i < values.size(); i++)
        EXPECT_EQ(values[i], int16_t(1 + i));
    // It never answers execution commands: a clear time-out, no hang.
    EXPECT_THROW(network.stop(selected[0]), TimeoutError);
}

namespace
{

// A node 6 that speaks protocol 6, and a node 7 whose description stops
// after its first named variable.
std::vector<Frame> unusable_nodes_answer(const Frame &frame)
{
    std::vector<Frame> replies;
    auto send = [&](const Message &message, uint16_t source) {
        replies.push_back(encode(message, source));
    };
    Message message = decode(frame);
    if (std::holds_alternative<ListNodes>(message)) {
        send(NodePresent{ 6 }, 6);
        send(NodePresent{ 5 }, 7);
    } else if (const auto *get = std::get_if<GetNodeDescription>(&message)) {
        if (get->dest == 6) {
            send(Description{ "future", 6, 100, 16, 40, 1, 0, 0 }, 6);
            send(NamedVariableDescription{ { "id", 1 } }, 6);
        } else {
            send(Description{ "halting", 5, 100, 16, 40, 2, 1, 0 }, 7);
            send(NamedVariableDescription{ { "id", 1 } }, 7);
        }
    }
    return replies;
}

} // namespace

// "no node 'all' on the network" said nothing of why: each node that
// answered is named with what is wrong with it.
TEST(NetworkModel, SaysWhyTheNodesThatAnsweredCannotBeUsed)
{
    console_test::ScriptedPeer fake(unusable_nodes_answer);
    Network network(Milliseconds(300));
    network.connect(fake.target());
    network.discover();
    ASSERT_EQ(network.node_keys().size(), 2u);
    try {
        network.select("all");
        FAIL() << "selected an unusable node";
    } catch (const NetworkError &error) {
        std::string text = error.what();
        EXPECT_NE(text.find("future 6 speaks protocol 6, this tool speaks protocols 4 and 5"),
                  std::string::npos)
          << text;
        EXPECT_NE(text.find("node 7 on " + fake.target() +
                            " (halting) did not finish describing itself within 300 ms: 1 of 2 "
                            "named variables, 0 of 1 local events, 0 of 0 native functions"),
                  std::string::npos)
          << text;
    }
}

// A reconnect link (LinkPolicy::reconnect) follows epuck-emu going away and
// coming back on the same port: it starts down without an exception, comes
// up with the emulator, goes down when it is killed (its nodes forgotten),
// and comes back by itself with the new emulator's nodes described.
TEST(NetworkLinks, AReconnectLinkFollowsTheEmulatorGoingAndComing)
{
    const uint16_t port = console_test::find_free_port();
    const Milliseconds limit(5000); // for what must happen (attempts are 500 ms apart)
    Network network;
    std::vector<std::pair<LinkState, std::string>> changes;
    network.set_link_listener([&](size_t target, LinkState state, const std::string &reason) {
        EXPECT_EQ(target, 0u);
        changes.push_back({ state, reason });
    });
    size_t target = network.connect("tcp:127.0.0.1;" + std::to_string(port), LinkPolicy::reconnect);
    EXPECT_EQ(network.link_state(target), LinkState::down);
    network.wait_until([&] { return !changes.empty(); }, limit);
    ASSERT_EQ(changes.size(), 1u);
    EXPECT_EQ(changes[0].first, LinkState::down);
    EXPECT_NE(changes[0].second.find("cannot connect"), std::string::npos) << changes[0].second;
    EXPECT_EQ(network.link_error(target), changes[0].second);
    EXPECT_THROW(network.send(target, ListNodes{ PROTOCOL_VERSION }), TransportError);

    auto described = [&](size_t count) {
        return [&network, count] {
            std::vector<NodeKey> keys = network.node_keys();
            return keys.size() == count && std::all_of(keys.begin(), keys.end(), [&](NodeKey key) {
                       return network.node(key).described;
                   });
        };
    };
    {
        Emulator emulator(2, {}, port);
        ASSERT_TRUE(network.wait_until(described(2), limit));
        EXPECT_EQ(network.link_state(target), LinkState::up);
        EXPECT_EQ(changes.back().first, LinkState::up);
        emulator.kill_now();
        ASSERT_TRUE(
          network.wait_until([&] { return network.link_state(target) == LinkState::down; }, limit));
        EXPECT_TRUE(network.node_keys().empty());
        EXPECT_EQ(changes.back().first, LinkState::down);
    }
    Emulator emulator(3, {}, port);
    ASSERT_TRUE(network.wait_until(described(3), limit));
    EXPECT_EQ(network.link_state(target), LinkState::up);
    EXPECT_TRUE(network.link_error(target).empty());
    EXPECT_EQ(network.select("all").size(), 3u);
}

// The default policy fails fast: a link that drops is an error of poll().
TEST(NetworkLinks, AFailFastLinkThatDropsIsAnError)
{
    auto emulator = std::make_unique<Emulator>(1);
    Network network;
    network.connect(emulator->target());
    network.discover();
    emulator->kill_now();
    EXPECT_THROW(network.wait_until([] { return false; }, Milliseconds(3000)), TransportError);
}

// wake() from another thread ends a poll() long before its time.
TEST(NetworkLinks, WakeEndsAPollFromAnotherThread)
{
    Emulator emulator(1);
    Network network;
    network.connect(emulator.target());
    network.discover();
    const Milliseconds long_poll(30000);
    std::thread waker([&] {
        std::this_thread::sleep_for(Milliseconds(50));
        network.wake();
    });
    auto start = Clock::now();
    network.poll(long_poll);
    auto waited = Clock::now() - start;
    waker.join();
    EXPECT_LT(waited, long_poll / 2);
    // Woken before it starts, the next poll returns at once too.
    network.wake();
    start = Clock::now();
    network.poll(long_poll);
    EXPECT_LT(Clock::now() - start, long_poll / 2);
}
