// Robustness of the node against what a byte stream may bring: large
// variable requests, frames split anywhere, and a long random stream of
// valid, mutated and garbage frames under the sanitizers.

#include "node_harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace node_test;

namespace
{

const Bytes list_nodes = make_frame(0, 0xA011, words({ 5 }));
const Bytes node_present = make_frame(1, 0x900C, words({ 5 }));

uint16_t word_at(const Bytes &frame, size_t offset)
{
    return uint16_t(frame[offset] | frame[offset + 1] << 8);
}

// --- large VARIABLES answers -------------------------------------------------

TEST(NodeVariables, LargeRequestsAreSplitInto257WordAnswers)
{
    Harness harness(preset("refnode"), 1); // 1060 variables
    int16_t *variables = harness.node().vm.memory.variables;
    auto value_at = [](uint32_t address) { return int16_t(address * 7 - 3000); };
    for (uint16_t i = 0; i < 1060; i++)
        variables[i] = value_at(i);

    struct Request {
        uint16_t start, length;
        std::vector<uint16_t> expected_parts; // words per answer
    };
    const Request requests[] = {
        { 10, 600, { 257, 257, 86 } },
        { 0, 1060, { 257, 257, 257, 257, 32 } },
        { 0, 0xFFFF, { 257, 257, 257, 257, 32 } }, // clamped to the memory
        { 1000, 257, { 60 } },
        { 3, 257, { 257 } },
        { 3, 258, { 257, 1 } },
    };
    for (const Request &request : requests) {
        SCOPED_TRACE(std::to_string(request.start) + "+" + std::to_string(request.length));
        harness.frames.clear();
        harness.feed(make_frame(0, 0xA00B, words({ 1, request.start, request.length })));
        ASSERT_EQ(harness.frames.size(), request.expected_parts.size());
        uint32_t address = request.start;
        for (size_t part = 0; part < request.expected_parts.size(); part++) {
            const Bytes &frame = harness.frames[part];
            uint16_t count = request.expected_parts[part];
            ASSERT_EQ(word_at(frame, 0), 2 + 2 * count);
            EXPECT_EQ(word_at(frame, 4), 0x9005);
            EXPECT_EQ(word_at(frame, 6), address);
            for (uint16_t i = 0; i < count; i++)
                ASSERT_EQ(int16_t(word_at(frame, 8 + 2 * i)), value_at(address + i));
            address += count;
        }
    }
    EXPECT_TRUE(harness.bad.empty());
}

TEST(NodeVariables, SetVariablesOfAFullPayloadStopsAtTheEnd)
{
    Harness harness(preset("tiny"), 1); // 40 variables
    Bytes payload = words({ 1, 20 });
    for (uint16_t i = 0; i < 256; i++) {
        payload.push_back(uint8_t(i + 1));
        payload.push_back(0);
    }
    harness.feed(make_frame(0, 0xA00C, payload));
    const vm_memory &memory = harness.node().vm.memory;
    for (uint16_t i = 20; i < 40; i++)
        EXPECT_EQ(memory.variables[i], i - 19);
    EXPECT_TRUE(harness.canaries_intact());
}

// --- framing -------------------------------------------------------------------

TEST(NodeReceive, TakesOneFrameAtATime)
{
    Harness harness(preset("tiny"), 1);
    Bytes two = list_nodes;
    two.insert(two.end(), list_nodes.begin(), list_nodes.end());
    // The node takes the first frame and leaves the second to the caller.
    EXPECT_EQ(node_receive(&harness.node(), two.data(), uint16_t(two.size()), 0), 8);
    EXPECT_EQ(node_receive(&harness.node(), two.data() + 8, 8, 0), 0);
    EXPECT_FALSE(node_receive_byte(&harness.node(), two[8], 0));
    node_poll(&harness.node(), 0);
    EXPECT_EQ(node_receive(&harness.node(), two.data() + 8, 8, 0), 8);
    node_poll(&harness.node(), 0);
    ASSERT_EQ(harness.frames.size(), 2u);
    EXPECT_EQ(hex(harness.frames[1]), hex(node_present));
}

// What node_receive_wanted says is what the frame lacks: the header, then
// the payload its header announced, nothing while the frame waits; after a
// stall the partial frame is gone and a header is wanted again.
TEST(NodeReceive, WantsWhatTheFrameLacks)
{
    Harness harness(preset("tiny"), 1);
    node_state *node = &harness.node();
    EXPECT_EQ(node_receive_wanted(node, 0), 6);
    EXPECT_EQ(node_receive(node, list_nodes.data(), 4, 0), 4);
    EXPECT_EQ(node_receive_wanted(node, 0), 2);
    EXPECT_EQ(node_receive(node, list_nodes.data() + 4, 2, 0), 2);
    EXPECT_EQ(node_receive_wanted(node, 0), 2); // one word of payload
    EXPECT_EQ(node_receive(node, list_nodes.data() + 6, 2, 0), 2);
    EXPECT_EQ(node_receive_wanted(node, 0), 0);
    node_poll(node, 0);
    EXPECT_EQ(node_receive_wanted(node, 0), 6);

    EXPECT_EQ(node_receive(node, list_nodes.data(), 7, 0), 7);
    EXPECT_EQ(node_receive_wanted(node, 0), 1);
    EXPECT_EQ(node_receive_wanted(node, 10000), 6); // ten seconds later
    EXPECT_EQ(node->errors.truncated, 1);
    ASSERT_EQ(harness.frames.size(), 1u);
    EXPECT_EQ(hex(harness.frames[0]), hex(node_present));
}

// Bytes placed straight into the frame (node_receive_place) are counted as
// received ones, and node_receive_placed answers what the frame lacks next,
// as node_receive_wanted would.
TEST(NodeReceive, PlacedBytesAnswerWhatTheFrameLacksNext)
{
    Harness harness(preset("tiny"), 1);
    node_state *node = &harness.node();
    auto place = [&](size_t from, uint16_t count, uint32_t now) {
        std::copy_n(list_nodes.data() + from, count, node_receive_place(node));
        return node_receive_placed(node, count, now);
    };
    ASSERT_EQ(node_receive_wanted(node, 0), 6);
    EXPECT_EQ(place(0, 6, 0), 2); // the header asks for one word of payload
    EXPECT_EQ(place(6, 2, 1), 0); // complete: nothing until node_poll
    EXPECT_EQ(node_receive_placed(node, 0, 1), node_receive_wanted(node, 1));
    node_poll(node, 1);
    ASSERT_EQ(harness.frames.size(), 1u);
    EXPECT_EQ(hex(harness.frames[0]), hex(node_present));
    EXPECT_EQ(place(0, 4, 2), 2);
    EXPECT_EQ(node_receive_placed(node, 0, 10000), 6); // a stall drops the partial frame
    EXPECT_EQ(node->errors.truncated, 1);
}

TEST(NodeReceive, ClockWrapAroundIsNotAStall)
{
    Harness harness(preset("tiny"), 1);
    harness.now = 0xFFFFFF00u;
    harness.feed(Bytes(list_nodes.begin(), list_nodes.begin() + 4));
    harness.now += 0x180; // wraps to 0x80: 384 ms later
    harness.feed(Bytes(list_nodes.begin() + 4, list_nodes.end()));
    ASSERT_EQ(harness.frames.size(), 1u);
    EXPECT_EQ(harness.node().errors.truncated, 0);
}

TEST(NodeReceive, ErrorCountersSaturate)
{
    Harness harness(preset("tiny"), 1);
    Bytes wrong = make_frame(0, 0xA003, words({ 2 }));
    Bytes many;
    for (int i = 0; i < 70000; i++)
        many.insert(many.end(), wrong.begin(), wrong.end());
    harness.feed(many);
    EXPECT_EQ(harness.node().errors.wrong_destination, 0xFFFF);
}

// --- random streams ------------------------------------------------------------

class StreamGenerator
{
  public:
    explicit StreamGenerator(uint32_t seed)
      : random_(seed)
    {
    }

    unsigned below(unsigned limit)
    {
        return unsigned(random_() % limit);
    }

    // A host command to node 1 (or sometimes another), with fields in
    // ranges that reach the interesting paths.
    Bytes command()
    {
        uint16_t type = uint16_t(0xA000 + below(0x12));
        uint16_t dest = below(8) == 0 ? uint16_t(below(3)) : 1;
        Bytes payload;
        switch (type) {
        case 0xA000:
        case 0xA011: payload = words({ uint16_t(below(7)) }); break;
        case 0xA001: {
            payload = words({ dest, uint16_t(below(80)) });
            unsigned count = below(40);
            for (unsigned i = 0; i < count; i++)
                append(payload, program_word());
            break;
        }
        case 0xA008:
        case 0xA009: payload = words({ dest, uint16_t(below(70)) }); break;
        case 0xA00B: payload = words({ dest, uint16_t(below(1100)), uint16_t(below(600)) }); break;
        case 0xA00C: {
            payload = words({ dest, uint16_t(below(1100)) });
            unsigned count = below(20);
            for (unsigned i = 0; i < count; i++)
                append(payload, uint16_t(random_()));
            break;
        }
        case 0xA00D: // hooks: harmless here
        case 0xA00E:
        case 0xA00F:
        case 0xA010: payload = words({ dest, 5 }); break;
        default: payload = words({ dest });
        }
        return make_frame(0, type, payload);
    }

    Bytes user_event()
    {
        Bytes payload;
        unsigned count = below(8) == 0 ? below(259) : below(6);
        for (unsigned i = 0; i < count; i++)
            append(payload, uint16_t(random_()));
        return make_frame(uint16_t(below(5)), uint16_t(below(8)), payload);
    }

    Bytes mutated(Bytes frame)
    {
        switch (below(5)) {
        case 0: // flip bytes
            for (unsigned i = 0, n = 1 + below(3); i < n; i++)
                frame[below(unsigned(frame.size()))] = uint8_t(random_());
            break;
        case 1: // truncate
            frame.resize(below(unsigned(frame.size())));
            break;
        case 2: // lie about the length
            frame[0] = uint8_t(random_());
            frame[1] = uint8_t(below(4));
            break;
        case 3: // extra bytes
            for (unsigned i = 0, n = 1 + below(9); i < n; i++)
                frame.push_back(uint8_t(random_()));
            break;
        default: // an oversize length
            frame[0] = uint8_t(random_());
            frame[1] = uint8_t(3 + below(253));
        }
        return frame;
    }

    Bytes garbage()
    {
        Bytes bytes(below(40));
        for (uint8_t &byte : bytes)
            byte = uint8_t(random_());
        return bytes;
    }

  private:
    // Mostly valid instructions over small addresses, so that programs run.
    uint16_t program_word()
    {
        if (below(4) == 0)
            return uint16_t(random_());
        return uint16_t(below(16) << 12 | below(64));
    }
    static void append(Bytes &bytes, uint16_t word)
    {
        bytes.push_back(uint8_t(word));
        bytes.push_back(uint8_t(word >> 8));
    }

    std::mt19937 random_;
};

TEST(NodeRandomStream, SurvivesAndEmitsOnlyWellFormedFrames)
{
    constexpr unsigned frames = 100000;
    constexpr unsigned check_every = 5000;
    StreamGenerator generator(20261122);
    Harness harness(preset("refnode"), 1);
    harness.poll_limit = 2; // random programs may loop forever
    unsigned answered_checks = 0;

    for (unsigned i = 1; i <= frames; i++) {
        Bytes input;
        switch (generator.below(10)) {
        case 0:
        case 1:
        case 2:
        case 3: input = generator.command(); break;
        case 4:
        case 5: input = generator.user_event(); break;
        case 6:
        case 7:
        case 8:
            input =
              generator.mutated(generator.below(2) ? generator.command() : generator.user_event());
            break;
        default: input = generator.garbage();
        }
        // Pauses, often long enough to end a resynchronisation or a stall.
        if (generator.below(4) == 0)
            harness.now += 100 + generator.below(900);
        harness.now += generator.below(3);
        harness.feed(input, generator.below(4) == 0);
        if (generator.below(20) == 0)
            node_raise_local_event(&harness.node(), 0);
        harness.frames.clear();

        if (i % check_every == 0) {
            // After a quiet line the node must answer LIST_NODES.
            harness.now += NODE_INTER_BYTE_TIMEOUT_MS + 1;
            harness.feed(list_nodes);
            bool present = false;
            for (const Bytes &frame : harness.frames)
                present = present || frame == node_present;
            EXPECT_TRUE(present) << "after frame " << i;
            answered_checks += present;
            harness.frames.clear();
        }
        ASSERT_TRUE(harness.bad.empty()) << "after frame " << i << ": " << harness.bad.front();
        ASSERT_TRUE(harness.canaries_intact()) << "after frame " << i;
    }
    const node_error_counters &errors = harness.node().errors;
    EXPECT_EQ(answered_checks, frames / check_every);
    // The stream reached every kind of drop.
    EXPECT_GT(errors.oversize, 0);
    EXPECT_GT(errors.truncated, 0);
    EXPECT_GT(errors.malformed, 0);
    EXPECT_GT(errors.wrong_destination, 0);
    EXPECT_GT(harness.frames_sent, frames / 10);
    RecordProperty("frames_sent", std::to_string(harness.frames_sent));
}

} // namespace
