// The bridge's payloads and topics against docs/mqtt.md: what the broker
// may send, as a table of payloads and the verdict each must get.

#include <gtest/gtest.h>

#include "tools/mqtt/broker_client.hpp"
#include "tools/mqtt/payloads.hpp"
#include "tools/mqtt/topics.hpp"

namespace
{

using namespace aseba::mqtt;

struct EventCase {
    const char *payload;
    std::vector<int16_t> arguments; // when accepted
    const char *error;              // part of the error, when refused
};

const EventCase EVENT_CASES[] = {
    { "", {}, nullptr },
    { "  \n", {}, nullptr },
    { "[]", {}, nullptr },
    { "[1,-2,32767,-32768]", { 1, -2, 32767, -32768 }, nullptr },
    { R"({"args":[5]})", { 5 }, nullptr },
    { R"({"args":[5],"extra":"ignored"})", { 5 }, nullptr },
    { "{}", {}, nullptr },
    { "not json", {}, "not JSON" },
    { "[1,", {}, "not JSON" },
    { "42", {}, "JSON object" },
    { R"("text")", {}, "JSON object" },
    { R"({"args":"x"})", {}, "must be an array" },
    { R"({"args":{"a":1}})", {}, "must be an array" },
    { "[32768]", {}, "outside -32768..32767" },
    { "[-32769]", {}, "outside -32768..32767" },
    { "[18446744073709551615]", {}, "outside -32768..32767" },
    { "[1.5]", {}, "not an integer" },
    { "[true]", {}, "not an integer" },
    { "[null]", {}, "not an integer" },
    { R"(["1"])", {}, "not an integer" },
    { "[1,2,3,4,5]", {}, "more than the 4" },
    { "[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]", {}, "nests" },
    { R"({"args":[1],"bridge":"b"})", {}, "\"seq\"" },
    { R"({"args":[1],"bridge":"b","seq":-1,"network":"n","node":1})", {}, "\"seq\"" },
    { R"({"args":[1],"bridge":"b","seq":1,"network":"n","node":70000})", {}, "\"node\"" },
    { R"({"args":[1],"bridge":7,"seq":1,"network":"n","node":1})", {}, "\"bridge\"" },
};

TEST(MqttPayloads, EventsFromTheBroker)
{
    for (const EventCase &test : EVENT_CASES) {
        SCOPED_TRACE(test.payload);
        if (test.error == nullptr) {
            EXPECT_EQ(read_event(test.payload, 4).arguments, test.arguments);
            continue;
        }
        try {
            read_event(test.payload, 4);
            ADD_FAILURE() << "accepted";
        } catch (const PayloadError &error) {
            EXPECT_NE(std::string(error.what()).find(test.error), std::string::npos)
              << error.what();
        }
    }
}

TEST(MqttPayloads, EventsRoundTripWithTheirOrigin)
{
    EventOrigin origin{ "5f0c2a9e8d1b4c37", 1042, "lab-pc-1", 3 };
    EventPayload read = read_event(write_event({ 2, -7 }, origin, "e-puck", 1717171717171), 32);
    EXPECT_EQ(read.arguments, (std::vector<int16_t>{ 2, -7 }));
    ASSERT_TRUE(read.origin.has_value());
    EXPECT_EQ(read.origin->bridge, origin.bridge);
    EXPECT_EQ(read.origin->sequence, 1042u);
    EXPECT_EQ(read.origin->network, "lab-pc-1");
    EXPECT_EQ(read.origin->node, 3);
}

TEST(MqttPayloads, Commands)
{
    Command stop = read_command(R"({"command":"stop","request":{"id":[1,2]}})");
    EXPECT_EQ(stop.kind, CommandKind::stop);
    EXPECT_EQ(stop.request, R"({"id":[1,2]})");
    Command load = read_command(R"({"command":"load","program":"var a = 1"})");
    EXPECT_EQ(load.kind, CommandKind::load);
    EXPECT_EQ(load.program, "var a = 1");
    const std::pair<const char *, const char *> refused[] = {
        { "", "not JSON" },
        { "[]", "JSON object" },
        { "{}", "\"command\"" },
        { R"({"command":"fly"})", "unknown command" },
        { R"({"command":7})", "\"command\"" },
        { R"({"command":"load"})", "\"program\"" },
        { R"({"command":"load","program":3})", "\"program\"" },
    };
    for (const auto &[payload, error] : refused) {
        SCOPED_TRACE(payload);
        try {
            read_command(payload);
            ADD_FAILURE() << "accepted";
        } catch (const PayloadError &caught) {
            EXPECT_NE(std::string(caught.what()).find(error), std::string::npos) << caught.what();
        }
    }
}

TEST(MqttPayloads, NamesThatAreNotUtf8DoNotBreakThePayload)
{
    aseba::client::Node node;
    node.described = true;
    node.description.name = "e-puck\xff";
    EXPECT_NE(write_node("n", node).find("e-puck\xef\xbf\xbd"), std::string::npos);
}

TEST(MqttTopics, Layout)
{
    TopicLayout topics{ "lab/aseba" };
    EXPECT_EQ(topics.event("bad"), "lab/aseba/event/bad");
    EXPECT_EQ(topics.status("pc1"), "lab/aseba/bridge/pc1");
    EXPECT_EQ(topics.node("pc1", 3), "lab/aseba/network/pc1/node/3");
    EXPECT_EQ(topics.variable("pc1", 3, "camR[0:2]"),
              "lab/aseba/network/pc1/node/3/variable/camR[0:2]");
    EXPECT_EQ(topics.every_command("pc1"), "lab/aseba/network/pc1/node/+/command");
    EXPECT_EQ(topics.event_name("lab/aseba/event/bad"), "bad");
    EXPECT_FALSE(topics.event_name("lab/aseba/event/bad/more"));
    EXPECT_FALSE(topics.event_name("aseba/event/bad"));
    auto address = topics.command_address("lab/aseba/network/pc1/node/all/command");
    ASSERT_TRUE(address);
    EXPECT_EQ(address->network, "pc1");
    EXPECT_EQ(address->node, "all");
    EXPECT_FALSE(topics.command_address("lab/aseba/network/pc1/node/3/reply"));
    EXPECT_FALSE(topics.command_address("lab/aseba/network/pc1/command"));
}

TEST(MqttTopics, BrokerUrls)
{
    BrokerAddress plain = parse_broker_url("mqtt://broker.lab:1884");
    EXPECT_FALSE(plain.tls);
    EXPECT_EQ(plain.host, "broker.lab");
    EXPECT_EQ(plain.port, 1884);
    BrokerAddress secure = parse_broker_url("mqtts://broker.lab");
    EXPECT_TRUE(secure.tls);
    EXPECT_EQ(secure.port, 8883);
    EXPECT_EQ(parse_broker_url("localhost").port, 1883);
    EXPECT_EQ(parse_broker_url("[::1]:1999").host, "::1");
    for (const char *bad : { "http://x", "mqtt://", "mqtt://x:0", "mqtt://x:99999", "mqtt://x:y" })
        EXPECT_THROW(parse_broker_url(bad), BrokerError) << bad;
}

} // namespace
