// The client's wire codec against the byte examples of protocol.md (verified
// there against the reference tools), round trips of every message, and
// rejection of malformed input.

#include <gtest/gtest.h>

#include <random>

#include "tools/client/messages.hpp"

using namespace aseba;
using namespace aseba::client;

namespace
{

using Bytes = std::vector<uint8_t>;

Bytes with_string(Bytes bytes, const std::string &text)
{
    bytes.push_back(uint8_t(text.size()));
    bytes.insert(bytes.end(), text.begin(), text.end());
    return bytes;
}

// The one frame in `bytes`, which must hold exactly one.
Frame only_frame(const Bytes &bytes)
{
    FrameAssembler assembler;
    assembler.feed(bytes.data(), bytes.size());
    std::optional<Frame> frame = assembler.next();
    EXPECT_TRUE(frame.has_value());
    EXPECT_EQ(assembler.pending_bytes(), 0u);
    return frame.value_or(Frame{});
}

Bytes wire(const Message &message, uint16_t source = HOST_SOURCE)
{
    return serialize_frame(encode(message, source));
}

Frame frame_of(uint16_t type, Bytes payload, uint16_t source = 1)
{
    Frame frame;
    frame.source = source;
    frame.type = type;
    frame.payload = std::move(payload);
    return frame;
}

} // namespace

// §5.1: emit pong [30, 7] from node 1.
TEST(CodecExamples, UserEventFromNode)
{
    const Bytes bytes{ 0x04, 0x00, 0x01, 0x00, 0x01, 0x00, 0x1e, 0x00, 0x07, 0x00 };
    Frame frame = only_frame(bytes);
    EXPECT_EQ(frame.source, 1);
    auto event = std::get<UserEvent>(decode(frame));
    EXPECT_EQ(event.id, 1);
    EXPECT_EQ(event.arguments, (std::vector<int16_t>{ 30, 7 }));
    EXPECT_EQ(wire(UserEvent{ 1, { 30, 7 } }, 1), bytes);
}

// §6.7: asebacmd usermsg 0 10 20.
TEST(CodecExamples, UserEventFromHost)
{
    const Bytes bytes{ 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x0a, 0x00, 0x14, 0x00 };
    EXPECT_EQ(wire(UserEvent{ 0, { 10, 20 } }), bytes);
}

// §5.2: "refnode", sizes 512/64/1060, 5 variables, 1 local event, 30 natives.
TEST(CodecExamples, Description)
{
    Bytes bytes{
        0x16, 0x00, 0x01, 0x00, 0x00, 0x90, 0x07, 'r',  'e',  'f',  'n',  'o',  'd',  'e',
        0x05, 0x00, 0x00, 0x02, 0x40, 0x00, 0x24, 0x04, 0x05, 0x00, 0x01, 0x00, 0x1e, 0x00
    };
    auto description = std::get<Description>(decode(only_frame(bytes)));
    EXPECT_EQ(description.name, "refnode");
    EXPECT_EQ(description.protocol_version, 5);
    EXPECT_EQ(description.bytecode_size, 512);
    EXPECT_EQ(description.stack_size, 64);
    EXPECT_EQ(description.variables_size, 1060);
    EXPECT_EQ(description.named_variables_count, 5);
    EXPECT_EQ(description.local_events_count, 1);
    EXPECT_EQ(description.native_functions_count, 30);
    EXPECT_EQ(wire(description, 1), bytes);
}

// §5.3: size 32, "args".
TEST(CodecExamples, NamedVariableDescription)
{
    Bytes payload{ 0x20, 0x00, 0x04, 'a', 'r', 'g', 's' };
    auto variable = std::get<NamedVariableDescription>(
      decode(frame_of(NODE_MSG_NAMED_VARIABLE_DESCRIPTION, payload)));
    EXPECT_EQ(variable.variable.name, "args");
    EXPECT_EQ(variable.variable.size, 32);
    EXPECT_EQ(encode(variable, 1).payload, payload);
}

// §5.5: math.fill.
TEST(CodecExamples, NativeFunctionDescription)
{
    Bytes payload = with_string({}, "math.fill");
    payload = with_string(payload, "fills dest with constant value");
    payload.insert(payload.end(), { 0x02, 0x00, 0xff, 0xff });
    payload = with_string(payload, "dest");
    payload.insert(payload.end(), { 0x01, 0x00 });
    payload = with_string(payload, "value");
    auto native = std::get<NativeFunctionDescription>(
      decode(frame_of(NODE_MSG_NATIVE_FUNCTION_DESCRIPTION, payload)));
    EXPECT_EQ(native.function.name, "math.fill");
    EXPECT_EQ(native.function.description, "fills dest with constant value");
    ASSERT_EQ(native.function.parameters.size(), 2u);
    EXPECT_EQ(native.function.parameters[0].name, "dest");
    EXPECT_EQ(native.function.parameters[0].size, -1);
    EXPECT_EQ(native.function.parameters[1].name, "value");
    EXPECT_EQ(native.function.parameters[1].size, 1);
    EXPECT_EQ(encode(native, 1).payload, payload);
}

// §5.9, §5.10, §5.11, §5.13.
TEST(CodecExamples, NodeReports)
{
    const Bytes killed{ 0x02, 0x00, 0x01, 0x00, 0x08, 0x90, 0x0d, 0x00 };
    EXPECT_EQ(std::get<EventExecutionKilled>(decode(only_frame(killed))).pc, 13);
    EXPECT_EQ(wire(EventExecutionKilled{ 13 }, 1), killed);

    const Bytes sqrt_error =
      with_string({ 0x19, 0x00, 0x01, 0x00, 0x09, 0x90, 0x08, 0x00 }, "Negative input to sqrt");
    auto error = std::get<NodeSpecificError>(decode(only_frame(sqrt_error)));
    EXPECT_EQ(error.pc, 8);
    EXPECT_EQ(error.message, "Negative input to sqrt");
    EXPECT_EQ(wire(error, 1), sqrt_error);

    const Bytes state{ 0x04, 0x00, 0x01, 0x00, 0x0a, 0x90, 0x13, 0x00, 0x03, 0x00 };
    auto changed = std::get<ExecutionStateChanged>(decode(only_frame(state)));
    EXPECT_EQ(changed.pc, 19);
    EXPECT_EQ(changed.flags, 3);
    EXPECT_EQ(wire(changed, 1), state);

    const Bytes present{ 0x02, 0x00, 0x01, 0x00, 0x0c, 0x90, 0x05, 0x00 };
    EXPECT_EQ(std::get<NodePresent>(decode(only_frame(present))).version, 5);
    EXPECT_EQ(wire(NodePresent{ 5 }, 1), present);
}

// §6.1: the host side of the verified handshake.
TEST(CodecExamples, Handshake)
{
    EXPECT_EQ(wire(ListNodes{ 5 }), (Bytes{ 0x02, 0x00, 0x00, 0x00, 0x11, 0xa0, 0x05, 0x00 }));
    EXPECT_EQ(wire(GetDescription{ 5 }), (Bytes{ 0x02, 0x00, 0x00, 0x00, 0x00, 0xa0, 0x05, 0x00 }));
    EXPECT_EQ(wire(GetNodeDescription{ 1, 5 }),
              (Bytes{ 0x04, 0x00, 0x00, 0x00, 0x10, 0xa0, 0x01, 0x00, 0x05, 0x00 }));
}

// Host commands laid out as the table of §3 says (dest first, uint16 LE).
TEST(CodecExamples, HostCommands)
{
    EXPECT_EQ(wire(NodeCommand{ NODE_MSG_RUN, 2 }),
              (Bytes{ 0x02, 0x00, 0x00, 0x00, 0x03, 0xa0, 0x02, 0x00 }));
    EXPECT_EQ(wire(GetVariables{ 1, 0x0102, 257 }),
              (Bytes{ 0x06, 0x00, 0x00, 0x00, 0x0b, 0xa0, 0x01, 0x00, 0x02, 0x01, 0x01, 0x01 }));
    EXPECT_EQ(
      wire(SetVariables{ 1, 3, { -1, 2 } }),
      (Bytes{
        0x08, 0x00, 0x00, 0x00, 0x0c, 0xa0, 0x01, 0x00, 0x03, 0x00, 0xff, 0xff, 0x02, 0x00 }));
    EXPECT_EQ(wire(SetBytecode{ 1, 256, { 0x1234 } }),
              (Bytes{ 0x06, 0x00, 0x00, 0x00, 0x01, 0xa0, 0x01, 0x00, 0x00, 0x01, 0x34, 0x12 }));
    EXPECT_EQ(wire(BreakpointCommand{ NODE_MSG_BREAKPOINT_SET, 1, 19 }),
              (Bytes{ 0x04, 0x00, 0x00, 0x00, 0x08, 0xa0, 0x01, 0x00, 0x13, 0x00 }));
    // An empty program is still one SET_BYTECODE (§6.2).
    EXPECT_EQ(wire(SetBytecode{ 1, 0, {} }),
              (Bytes{ 0x04, 0x00, 0x00, 0x00, 0x01, 0xa0, 0x01, 0x00, 0x00, 0x00 }));
}

// Every message survives encode, the wire and decode unchanged.
TEST(CodecRoundTrip, EveryMessage)
{
    NativeFunction function{ "math.dot", "scalar product", { { "dest", 1 }, { "src1", -1 } } };
    std::vector<uint16_t> words(MAX_BYTECODE_CHUNK_WORDS, 0xBEEF);
    std::vector<int16_t> values(MAX_VARIABLES_WORDS, -7);
    const std::vector<Message> messages = {
        UserEvent{ 0x7FFF, std::vector<int16_t>(MAX_EVENT_WORDS, -32768) },
        UserEvent{ 0, {} },
        Description{ "e-puck", 5, 1024, 32, 500, 13, 2, 30 },
        NamedVariableDescription{ { "camR", 60 } },
        LocalEventDescription{ { "ir_sensors", "new proximity values" } },
        NativeFunctionDescription{ function },
        Disconnected{},
        Variables{ 3, values },
        ArrayAccessOutOfBounds{ 12, 8, 0xFFFF },
        DivisionByZero{ 4 },
        EventExecutionKilled{ 5 },
        NodeSpecificError{ 6, std::string(MAX_STRING_SIZE, 'x') },
        ExecutionStateChanged{ 7, 7 },
        BreakpointSetResult{ 8, 1 },
        NodePresent{ 5 },
        BootloaderDescription{ 2048, 4, 60 },
        BootloaderPageDataRead{ { 1, 2, 3, 4 } },
        BootloaderAck{ 0, std::nullopt },
        BootloaderAck{ BOOTLOADER_ERROR_PROGRAMMING_FAILED, 0x1234 },
        GetDescription{ 4 },
        ListNodes{ 5 },
        NodeCommand{ NODE_MSG_REBOOT, 9 },
        NodeCommand{ MSG_BOOTLOADER_RESET, 9 },
        SetBytecode{ 2, 256, words },
        BreakpointCommand{ NODE_MSG_BREAKPOINT_CLEAR, 2, 40 },
        GetVariables{ 2, 10, 20 },
        SetVariables{ 2, 10, std::vector<int16_t>(MAX_SET_VARIABLES_WORDS, 3) },
        GetNodeDescription{ 2, 5 },
        BootloaderPageCommand{ MSG_BOOTLOADER_WRITE_PAGE, 2, 77 },
        BootloaderPageDataWrite{ 2, { 9, 8, 7, 6 } },
    };
    Bytes stream;
    for (const Message &message : messages) {
        Bytes bytes = wire(message, 3);
        stream.insert(stream.end(), bytes.begin(), bytes.end());
    }
    // The whole stream fed one byte at a time gives back every message.
    FrameAssembler assembler;
    std::vector<Message> decoded;
    for (uint8_t byte : stream) {
        assembler.feed(&byte, 1);
        while (std::optional<Frame> frame = assembler.next()) {
            EXPECT_EQ(frame->source, 3);
            decoded.push_back(decode(*frame));
        }
    }
    ASSERT_EQ(decoded.size(), messages.size());
    for (size_t i = 0; i < messages.size(); i++) {
        SCOPED_TRACE(message_type_name(message_type(messages[i])));
        EXPECT_EQ(message_type(decoded[i]), message_type(messages[i]));
        EXPECT_EQ(encode(decoded[i]).payload, encode(messages[i]).payload);
    }
}

// Payload sizes of the largest messages hosts may send (§2: at most 516).
TEST(CodecLimits, LargestMessagesFit)
{
    EXPECT_EQ(
      encode(SetBytecode{ 1, 0, std::vector<uint16_t>(MAX_BYTECODE_CHUNK_WORDS) }).payload.size(),
      516u);
    EXPECT_EQ(encode(Variables{ 0, std::vector<int16_t>(MAX_VARIABLES_WORDS) }).payload.size(),
              516u);
    EXPECT_THROW(encode(SetBytecode{ 1, 0, std::vector<uint16_t>(MAX_BYTECODE_CHUNK_WORDS + 1) }),
                 ProtocolError);
    EXPECT_THROW(encode(UserEvent{ 1, std::vector<int16_t>(MAX_EVENT_WORDS + 1) }), ProtocolError);
    EXPECT_THROW(encode(NodeSpecificError{ 0, std::string(MAX_STRING_SIZE + 1, 'x') }),
                 ProtocolError);
    EXPECT_THROW(encode(UserEvent{ 0x8000, {} }), ProtocolError);
    EXPECT_THROW(encode(NodeCommand{ NODE_MSG_SET_BYTECODE, 1 }), ProtocolError);
    EXPECT_THROW(encode(BootloaderAck{ 2, std::nullopt }), ProtocolError);
}

struct MalformedCase {
    const char *name;
    uint16_t type;
    Bytes payload;
};

class MalformedFrames : public testing::TestWithParam<MalformedCase>
{
};

TEST_P(MalformedFrames, AreRejected)
{
    const MalformedCase &c = GetParam();
    EXPECT_THROW(decode(frame_of(c.type, c.payload)), ProtocolError) << c.name;
}

// Each layout one byte short or one byte long, strings that run past the end,
// odd word lists, reserved and unknown types.
INSTANTIATE_TEST_SUITE_P(
  Codec,
  MalformedFrames,
  testing::Values(
    MalformedCase{ "odd user event", 1, { 1, 0, 2 } },
    MalformedCase{ "short out of bounds", NODE_MSG_ARRAY_ACCESS_OUT_OF_BOUNDS, { 1, 0, 2, 0 } },
    MalformedCase{ "long division", NODE_MSG_DIVISION_BY_ZERO, { 1, 0, 2 } },
    MalformedCase{ "empty killed", NODE_MSG_EVENT_EXECUTION_KILLED, {} },
    MalformedCase{ "short state", NODE_MSG_EXECUTION_STATE_CHANGED, { 1, 0, 2 } },
    MalformedCase{ "long state", NODE_MSG_EXECUTION_STATE_CHANGED, { 1, 0, 2, 0, 0, 0 } },
    MalformedCase{ "short present", NODE_MSG_NODE_PRESENT, { 5 } },
    MalformedCase{ "string past end", NODE_MSG_NODE_SPECIFIC_ERROR, { 0, 0, 5, 'a', 'b' } },
    MalformedCase{ "no string", NODE_MSG_NAMED_VARIABLE_DESCRIPTION, { 1, 0 } },
    MalformedCase{ "short description", NODE_MSG_DESCRIPTION, { 1, 'x', 5, 0 } },
    MalformedCase{ "missing parameter",
                   NODE_MSG_NATIVE_FUNCTION_DESCRIPTION,
                   { 1, 'f', 0, 1, 0, 1, 0 } },
    MalformedCase{ "odd variables", NODE_MSG_VARIABLES, { 0, 0, 1 } },
    MalformedCase{ "empty variables", NODE_MSG_VARIABLES, {} },
    MalformedCase{ "ack without address", MSG_BOOTLOADER_ACK, { 2, 0 } },
    MalformedCase{ "ack with address", MSG_BOOTLOADER_ACK, { 0, 0, 1, 0 } },
    MalformedCase{ "short page data", MSG_BOOTLOADER_PAGE_DATA_READ, { 1, 2, 3 } },
    MalformedCase{ "empty run", NODE_MSG_RUN, {} },
    MalformedCase{ "long run", NODE_MSG_RUN, { 1, 0, 0 } },
    MalformedCase{ "odd bytecode", NODE_MSG_SET_BYTECODE, { 1, 0, 0, 0, 1 } },
    MalformedCase{ "unknown node message", 0x900D, { 0, 0 } },
    MalformedCase{ "unknown command", 0xA012, { 1, 0 } },
    MalformedCase{ "unknown bootloader", 0x8007, { 1, 0 } },
    MalformedCase{ "invalid", MSG_INVALID, {} },
    MalformedCase{ "oversized", 1, Bytes(MAX_PAYLOAD_SIZE + 2, 0) }));

// A header announcing more than 516 bytes cannot be followed: the stream is
// refused from then on, and the frames before it still come out.
TEST(FrameAssembler, RefusesImpossibleLength)
{
    Bytes bytes = wire(NodePresent{ 5 }, 1);
    bytes.insert(bytes.end(), { 0x05, 0x02, 0x01, 0x00, 0x01, 0x00 }); // len 517
    FrameAssembler assembler;
    assembler.feed(bytes.data(), bytes.size());
    EXPECT_TRUE(assembler.next().has_value());
    EXPECT_THROW(assembler.next(), ProtocolError);
    EXPECT_THROW(assembler.feed(bytes.data(), 1), ProtocolError);
}

TEST(FrameAssembler, WaitsForWholeFrames)
{
    Bytes bytes = wire(UserEvent{ 2, { 1, 2, 3 } }, 4);
    FrameAssembler assembler;
    assembler.feed(bytes.data(), bytes.size() - 1);
    EXPECT_FALSE(assembler.next().has_value());
    assembler.feed(bytes.data() + bytes.size() - 1, 1);
    std::optional<Frame> frame = assembler.next();
    ASSERT_TRUE(frame.has_value());
    EXPECT_EQ(frame->payload.size(), 6u);
    EXPECT_FALSE(assembler.next().has_value());
}

// Random frames: decoding either succeeds or throws ProtocolError, and what
// it accepts encodes back to the same payload (layouts are exact).
TEST(CodecRobustness, RandomFramesNeverCrash)
{
    std::mt19937 random(20261122);
    const uint16_t interesting_types[] = { 0x0001, 0x8000, 0x8003, 0x8004, 0x8006, 0x9000, 0x9001,
                                           0x9003, 0x9005, 0x9009, 0x900A, 0x900C, 0xA000, 0xA001,
                                           0xA008, 0xA00B, 0xA00C, 0xA010, 0xA011, 0xA012, 0xFFFF };
    unsigned accepted = 0;
    for (int i = 0; i < 20000; i++) {
        Frame frame;
        frame.source = uint16_t(random());
        frame.type = interesting_types[random() % std::size(interesting_types)];
        frame.payload.resize(random() % 40);
        for (uint8_t &byte : frame.payload)
            byte = uint8_t(random() % 4 == 0 ? random() : random() % 3);
        try {
            Message message = decode(frame);
            accepted++;
            EXPECT_EQ(encode(message).payload, frame.payload);
            EXPECT_EQ(message_type(message), frame.type);
        } catch (const ProtocolError &) {
        }
    }
    EXPECT_GT(accepted, 0u);
}
