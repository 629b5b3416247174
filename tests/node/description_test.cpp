// Descriptions: the sequence of messages, strings cut to what the wire
// allows, the fingerprint of protocol.md §9; and the firmware's side of the
// node (local events, its own user events).

#include "node_harness.hpp"

#include <gtest/gtest.h>

#include <cstring>

#include "tests/support/native_table.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "nat_standard.h"
}

using namespace node_test;

namespace
{

const Bytes list_nodes = make_frame(0, 0xA011, words({ 5 }));

Bytes get_node_description(uint16_t dest)
{
    return make_frame(0, 0xA010, words({ dest, 5 }));
}

uint16_t type_of(const Bytes &frame)
{
    return uint16_t(frame[4] | frame[5] << 8);
}

uint16_t payload_length(const Bytes &frame)
{
    return uint16_t(frame[0] | frame[1] << 8);
}

// --- CRC and fingerprint, written from protocol.md §9 -----------------------

TEST(NodeCrc, MatchesTheXmodemCheckValue)
{
    // The catalogue check value of CRC-16/XMODEM over "123456789".
    const char text[] = "123456789";
    EXPECT_EQ(node_crc16(0, reinterpret_cast<const uint8_t *>(text), 9), 0x31C3);
    EXPECT_EQ(node_crc16(0, nullptr, 0), 0);
}

struct SpecCrc {
    uint16_t crc = 0;
    void byte(uint8_t value)
    {
        crc ^= uint16_t(value << 8);
        for (int bit = 0; bit < 8; bit++)
            crc = (crc & 0x8000) ? uint16_t((crc << 1) ^ 0x1021) : uint16_t(crc << 1);
    }
    void u16(uint16_t value)
    {
        byte(uint8_t(value & 0xFF));
        byte(uint8_t(value >> 8));
    }
    void string(const std::string &text)
    {
        for (char c : text)
            byte(uint8_t(c));
        if (text.size() % 2)
            byte(0);
    }
};

uint16_t spec_fingerprint(const Preset &preset)
{
    const node_description &description = *preset.description;
    SpecCrc crc;
    crc.u16(preset.bytecode_size);
    crc.u16(preset.variables_size);
    crc.u16(preset.stack_size);
    for (uint16_t i = 0; i < description.variable_count; i++) {
        crc.u16(description.variables[i].size);
        crc.string(description.variables[i].name);
    }
    for (uint16_t i = 0; i < description.local_event_count; i++)
        crc.string(description.local_events[i].name);
    for (const aseba::NativeFunction &native : aseba::native_functions(*description.natives)) {
        crc.string(native.name);
        for (const aseba::NativeParameter &parameter : native.parameters) {
            crc.u16(uint16_t(parameter.size));
            crc.string(parameter.name);
        }
    }
    return crc.crc;
}

TEST(NodeFingerprint, FollowsTheSpecification)
{
    for (const char *name : { "tiny", "refnode" }) {
        const Preset &p = preset(name);
        Harness harness(p, 1);
        EXPECT_EQ(node_fingerprint(&harness.node()), spec_fingerprint(p)) << name;
        EXPECT_EQ(node_description_fingerprint(
                    p.description, p.bytecode_size, p.stack_size, p.variables_size),
                  spec_fingerprint(p))
          << name;
    }
}

TEST(NodeFingerprint, ChangesWithTheSizesAndTheirOrder)
{
    const Preset &p = preset("tiny");
    uint16_t base = node_description_fingerprint(p.description, 64, 16, 40);
    EXPECT_NE(base, node_description_fingerprint(p.description, 65, 16, 40));
    // Stack and variables sizes are not interchangeable.
    EXPECT_NE(node_description_fingerprint(p.description, 64, 16, 40),
              node_description_fingerprint(p.description, 64, 40, 16));
}

// --- the description sequence ----------------------------------------------

TEST(NodeDescription, SendsAllPartsInOrder)
{
    Harness harness(preset("refnode"), 1);
    harness.feed(get_node_description(1));
    const uint16_t native_count = vm_native_count(&nat_standard_table);
    ASSERT_EQ(harness.frames.size(), 1u + 5 + 1 + native_count);
    EXPECT_EQ(type_of(harness.frames[0]), 0x9000);
    for (size_t i = 1; i <= 5; i++)
        EXPECT_EQ(type_of(harness.frames[i]), 0x9001);
    EXPECT_EQ(type_of(harness.frames[6]), 0x9002);
    for (size_t i = 0; i < native_count; i++) {
        const Bytes &frame = harness.frames[7 + i];
        EXPECT_EQ(type_of(frame), 0x9003);
        // Natives in NATIVE_CALL order: the name comes first.
        std::string name = aseba::native_function(nat_standard_table, uint16_t(i)).name;
        EXPECT_EQ(std::string(frame.begin() + 7, frame.begin() + 7 + frame[6]), name);
    }
    EXPECT_TRUE(harness.bad.empty()) << harness.bad.front();
}

// The bytes of `text`.
Bytes bytes_of(const std::string &text)
{
    return Bytes(text.begin(), text.end());
}

// `first` then `second`.
Bytes operator+(Bytes first, const Bytes &second)
{
    first.insert(first.end(), second.begin(), second.end());
    return first;
}

// A packed native description (vm.h): stack words, name, documentation,
// parameters.
std::string packed(int stack_words,
                   const std::string &name,
                   const std::string &documentation,
                   const std::vector<std::pair<int, std::string>> &parameters)
{
    std::string description = char(stack_words) + name + '\x1F' + documentation;
    for (const auto &[size, parameter] : parameters)
        description += char(0x10 + size) + parameter;
    return description;
}

// A description with strings longer than the wire allows.
struct LongStrings {
    std::string long_name = std::string(300, 'n');
    // 254 ASCII bytes then a 3-byte character: the cut must not split it.
    std::string utf8_name = std::string(254, 'u') + "\xE2\x82\xAC" + "tail";
    std::string long_text = std::string(400, 'd');
    // Its documentation cut to 255 bytes; the message fits then.
    std::string cut = packed(2, "cut", long_text, { { -1, std::string(200, 'p') } });
    // More than a message holds even with its texts cut: sent by name alone.
    std::string too_long = packed(3,
                                  long_name,
                                  long_text,
                                  { { -1, std::string(200, 'a') },
                                    { -2, std::string(200, 'b') },
                                    { -3, std::string(200, 'c') } });
    std::string many =
      packed(0, "many", "", std::vector<std::pair<int, std::string>>(200, { 1, "p" }));
    vm_native natives[3] = { { nullptr, cut.c_str() },
                             { nullptr, too_long.c_str() },
                             { nullptr, many.c_str() } };
    test_support::OneModuleTable table{ natives, 3 };
    node_named_variable variables[3];
    node_local_event events[1];
    node_description description{};

    LongStrings()
    {
        variables[0] = { "id", 1 };
        variables[1] = { "source", 1 };
        variables[2] = { utf8_name.c_str(), 4 };
        events[0] = { long_name.c_str(), long_text.c_str() };
        description = { long_name.c_str(), 5, variables, 3, events, 1, &table.table() };
    }
};

TEST(NodeDescription, CutsLongStringsToWellFormedMessages)
{
    LongStrings strings;
    Preset p{ "long", &strings.description, 64, 16, 40 };
    Harness harness(p, 1);
    harness.feed(get_node_description(1));
    ASSERT_EQ(harness.frames.size(), 1u + 3 + 1 + 3);
    for (const std::string &problem : harness.bad)
        ADD_FAILURE() << problem;

    const Bytes &description = harness.frames[0];
    EXPECT_EQ(description[6], 255); // name cut to 255 bytes
    EXPECT_EQ(payload_length(description), 1 + 255 + 14);

    const Bytes &utf8 = harness.frames[3]; // size, then the name
    EXPECT_EQ(utf8[8], 254) << "the 3-byte character must not be split";

    const Bytes &event = harness.frames[4];
    EXPECT_EQ(event[6], 255);
    EXPECT_EQ(event[6 + 1 + 255], 255);
    EXPECT_EQ(payload_length(event), 1 + 255 + 1 + 255);

    // "cut": its documentation cut to 255 bytes.
    const Bytes &cut = harness.frames[5];
    EXPECT_EQ(payload_length(cut), 1 + 3 + 1 + 255 + 2 + 2 + 1 + 200);
    EXPECT_EQ(cut[6 + 1 + 3], 255);

    // The others by name alone (cut to 255): no documentation, no parameter.
    const Bytes &too_long = harness.frames[6];
    EXPECT_EQ(hex(too_long),
              hex(make_frame(1, 0x9003, Bytes{ 255 } + Bytes(255, 'n') + Bytes{ 0, 0, 0 })));
    const Bytes &many = harness.frames[7];
    EXPECT_EQ(hex(many), hex(make_frame(1, 0x9003, Bytes{ 4, 'm', 'a', 'n', 'y', 0, 0, 0 })));

    // The fingerprint covers the names as sent.
    SpecCrc crc;
    crc.u16(64);
    crc.u16(40);
    crc.u16(16);
    crc.u16(1);
    crc.string("id");
    crc.u16(1);
    crc.string("source");
    crc.u16(4);
    crc.string(std::string(254, 'u'));
    crc.string(std::string(255, 'n')); // the local event
    crc.string("cut");
    crc.u16(uint16_t(-1));
    crc.string(std::string(200, 'p'));
    crc.string(std::string(255, 'n'));
    crc.string("many");
    EXPECT_EQ(node_fingerprint(&harness.node()), crc.crc);
}

// Bytes from 0x80 of a description stand for the words of its table's
// dictionary, or for themselves in a table without one.
TEST(NodeDescription, ExpandsTheWordsOfTheDictionary)
{
    const char words[] = "alpha\0beta\0";
    const vm_native list[] = { { nullptr,
                                 "\x01\x81.\x80\x1F"
                                 "\x80 and \x81\x11"
                                 "x\x81" } };
    node_named_variable variables[] = { { "id", 1 }, { "source", 1 }, { "args", 2 } };
    for (const char *dictionary : { words, static_cast<const char *>(nullptr) }) {
        test_support::OneModuleTable table(list, 1, dictionary);
        node_description description = { "words", 5, variables, 3, nullptr, 0, &table.table() };
        Preset p{ "words", &description, 16, 8, 8 };
        Harness harness(p, 1);
        harness.feed(get_node_description(1));
        ASSERT_EQ(harness.frames.size(), 5u);
        std::string name = dictionary ? "beta.alpha" : "\x81.\x80";
        std::string text = dictionary ? "alpha and beta" : "\x80 and \x81";
        std::string parameter = dictionary ? "xbeta" : "x\x81";
        Bytes payload = Bytes{ uint8_t(name.size()) } + bytes_of(name) +
                        Bytes{ uint8_t(text.size()) } + bytes_of(text) +
                        Bytes{ 1, 0, 1, 0, uint8_t(parameter.size()) } + bytes_of(parameter);
        EXPECT_EQ(hex(harness.frames[4]), hex(make_frame(1, 0x9003, payload)));
    }
}

TEST(NodeDescription, WorksWithoutNatives)
{
    node_named_variable variables[] = { { "id", 1 }, { "source", 1 }, { "args", 2 } };
    node_description description = { "bare", 5, variables, 3, nullptr, 0, nullptr };
    Preset p{ "bare", &description, 16, 8, 8 };
    Harness harness(p, 3);
    harness.feed(get_node_description(3));
    ASSERT_EQ(harness.frames.size(), 4u);
    EXPECT_EQ(
      hex(harness.frames[0]),
      hex(make_frame(
        3, 0x9000, Bytes{ 4, 'b', 'a', 'r', 'e', 5, 0, 16, 0, 8, 0, 8, 0, 3, 0, 0, 0, 0, 0 })));
    EXPECT_TRUE(harness.bad.empty());
}

// --- the firmware's side -----------------------------------------------------

// A program whose local events 0 and 1 each emit their own user event.
//   0: table of 2 entries: 0xFFFE -> 5, 0xFFFD -> 9
//   5: EMIT 10, 0, 0; STOP    9: EMIT 11, 0, 0; STOP
const std::vector<uint16_t> local_event_program = { 5, 0xFFFE, 5,      0xFFFD, 9, 0xB00A, 0,
                                                    0, 0x0000, 0xB00B, 0,      0, 0 };

Bytes set_bytecode(uint16_t dest, uint16_t start, const std::vector<uint16_t> &program)
{
    Bytes payload = words({ dest, start });
    for (uint16_t word : program) {
        payload.push_back(uint8_t(word));
        payload.push_back(uint8_t(word >> 8));
    }
    return make_frame(0, 0xA001, payload);
}

TEST(NodeLocalEvents, StartLowestIndexFirstOneAtATime)
{
    Harness harness(preset("tiny"), 1);
    harness.feed(set_bytecode(1, 0, local_event_program));
    harness.feed(make_frame(0, 0xA003, words({ 1 })));
    harness.frames.clear();

    EXPECT_TRUE(node_raise_local_event(&harness.node(), 1));
    EXPECT_TRUE(node_raise_local_event(&harness.node(), 0));
    EXPECT_FALSE(node_raise_local_event(&harness.node(), 2)); // tiny has 2
    harness.poll_until_idle();
    ASSERT_EQ(harness.frames.size(), 2u);
    EXPECT_EQ(hex(harness.frames[0]), hex(make_frame(1, 10, {})));
    EXPECT_EQ(hex(harness.frames[1]), hex(make_frame(1, 11, {})));
    // Raising an event twice before it starts runs it once.
    harness.frames.clear();
    node_raise_local_event(&harness.node(), 0);
    node_raise_local_event(&harness.node(), 0);
    harness.poll_until_idle();
    EXPECT_EQ(harness.frames.size(), 1u);
}

TEST(NodeUserEvents, FirmwareEventsAreWellFormedAndClamped)
{
    Harness harness(preset("tiny"), 9);
    std::vector<int16_t> values(300);
    for (size_t i = 0; i < values.size(); i++)
        values[i] = int16_t(i * 3 - 100);
    node_send_user_event(&harness.node(), 42, values.data(), 2);
    node_send_user_event(&harness.node(), 42, values.data(), 300);   // 258 at most
    node_send_user_event(&harness.node(), 0x8000, values.data(), 1); // not a user event
    ASSERT_EQ(harness.frames.size(), 2u);
    EXPECT_EQ(hex(harness.frames[0]),
              hex(make_frame(9, 42, words({ uint16_t(-100), uint16_t(-97) }))));
    EXPECT_EQ(payload_length(harness.frames[1]), 516);
    EXPECT_TRUE(harness.bad.empty());
}

TEST(NodeInit, StoresTheIdInTheFirstVariable)
{
    Harness harness(preset("tiny"), 0x1234);
    EXPECT_EQ(harness.node().vm.memory.variables[0], 0x1234);
    EXPECT_EQ(harness.node().vm.memory.args_size, 4); // the third named variable
}

} // namespace
