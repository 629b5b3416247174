// Payload layouts of protocol.md §5 (node to host) and §6 (host to node).

#include "messages.hpp"

#include <algorithm>
#include <cstdio>

namespace aseba::client
{

namespace
{

// Types whose payload is only `dest`.
constexpr uint16_t dest_only_types[] = {
    NODE_MSG_RESET,
    NODE_MSG_RUN,
    NODE_MSG_PAUSE,
    NODE_MSG_STEP,
    NODE_MSG_STOP,
    NODE_MSG_GET_EXECUTION_STATE,
    NODE_MSG_BREAKPOINT_CLEAR_ALL,
    NODE_MSG_WRITE_BYTECODE,
    NODE_MSG_REBOOT,
    NODE_MSG_SUSPEND_TO_RAM,
    MSG_BOOTLOADER_RESET,
};

bool is_dest_only(uint16_t type)
{
    return std::find(std::begin(dest_only_types), std::end(dest_only_types), type) !=
           std::end(dest_only_types);
}

struct TypeName {
    uint16_t type;
    const char *name;
};

constexpr TypeName type_names[] = {
    { MSG_BOOTLOADER_RESET, "BOOTLOADER_RESET" },
    { MSG_BOOTLOADER_READ_PAGE, "BOOTLOADER_READ_PAGE" },
    { MSG_BOOTLOADER_WRITE_PAGE, "BOOTLOADER_WRITE_PAGE" },
    { MSG_BOOTLOADER_PAGE_DATA_WRITE, "BOOTLOADER_PAGE_DATA_WRITE" },
    { MSG_BOOTLOADER_DESCRIPTION, "BOOTLOADER_DESCRIPTION" },
    { MSG_BOOTLOADER_PAGE_DATA_READ, "BOOTLOADER_PAGE_DATA_READ" },
    { MSG_BOOTLOADER_ACK, "BOOTLOADER_ACK" },
    { NODE_MSG_DESCRIPTION, "DESCRIPTION" },
    { NODE_MSG_NAMED_VARIABLE_DESCRIPTION, "NAMED_VARIABLE_DESCRIPTION" },
    { NODE_MSG_LOCAL_EVENT_DESCRIPTION, "LOCAL_EVENT_DESCRIPTION" },
    { NODE_MSG_NATIVE_FUNCTION_DESCRIPTION, "NATIVE_FUNCTION_DESCRIPTION" },
    { NODE_MSG_DISCONNECTED, "DISCONNECTED" },
    { NODE_MSG_VARIABLES, "VARIABLES" },
    { NODE_MSG_ARRAY_ACCESS_OUT_OF_BOUNDS, "ARRAY_ACCESS_OUT_OF_BOUNDS" },
    { NODE_MSG_DIVISION_BY_ZERO, "DIVISION_BY_ZERO" },
    { NODE_MSG_EVENT_EXECUTION_KILLED, "EVENT_EXECUTION_KILLED" },
    { NODE_MSG_NODE_SPECIFIC_ERROR, "NODE_SPECIFIC_ERROR" },
    { NODE_MSG_EXECUTION_STATE_CHANGED, "EXECUTION_STATE_CHANGED" },
    { NODE_MSG_BREAKPOINT_SET_RESULT, "BREAKPOINT_SET_RESULT" },
    { NODE_MSG_NODE_PRESENT, "NODE_PRESENT" },
    { NODE_MSG_GET_DESCRIPTION, "GET_DESCRIPTION" },
    { NODE_MSG_SET_BYTECODE, "SET_BYTECODE" },
    { NODE_MSG_RESET, "RESET" },
    { NODE_MSG_RUN, "RUN" },
    { NODE_MSG_PAUSE, "PAUSE" },
    { NODE_MSG_STEP, "STEP" },
    { NODE_MSG_STOP, "STOP" },
    { NODE_MSG_GET_EXECUTION_STATE, "GET_EXECUTION_STATE" },
    { NODE_MSG_BREAKPOINT_SET, "BREAKPOINT_SET" },
    { NODE_MSG_BREAKPOINT_CLEAR, "BREAKPOINT_CLEAR" },
    { NODE_MSG_BREAKPOINT_CLEAR_ALL, "BREAKPOINT_CLEAR_ALL" },
    { NODE_MSG_GET_VARIABLES, "GET_VARIABLES" },
    { NODE_MSG_SET_VARIABLES, "SET_VARIABLES" },
    { NODE_MSG_WRITE_BYTECODE, "WRITE_BYTECODE" },
    { NODE_MSG_REBOOT, "REBOOT" },
    { NODE_MSG_SUSPEND_TO_RAM, "SUSPEND_TO_RAM" },
    { NODE_MSG_GET_NODE_DESCRIPTION, "GET_NODE_DESCRIPTION" },
    { NODE_MSG_LIST_NODES, "LIST_NODES" },
};

const char *known_type_name(uint16_t type)
{
    for (const TypeName &entry : type_names)
        if (entry.type == type)
            return entry.name;
    return nullptr;
}

void write_words(PayloadWriter &writer, const std::vector<int16_t> &values)
{
    for (int16_t value : values)
        writer.i16(value);
}

std::vector<int16_t> read_words(PayloadReader &reader, const char *what)
{
    if (reader.remaining() % 2 != 0)
        throw ProtocolError(std::string(what) +
                            ": odd number of bytes where int16 words are expected");
    std::vector<int16_t> values;
    while (reader.remaining() > 0)
        values.push_back(reader.i16());
    return values;
}

void require_type(bool valid, uint16_t type, const char *structure)
{
    if (!valid)
        throw ProtocolError(std::string(structure) + " cannot carry message type " +
                            message_type_name(type));
}

// Encoding: one overload per message, each writing its payload.
struct Encoder {
    PayloadWriter &out;

    void operator()(const UserEvent &m)
    {
        write_words(out, m.arguments);
    }
    void operator()(const Description &m)
    {
        out.string(m.name);
        out.u16(m.protocol_version);
        out.u16(m.bytecode_size);
        out.u16(m.stack_size);
        out.u16(m.variables_size);
        out.u16(m.named_variables_count);
        out.u16(m.local_events_count);
        out.u16(m.native_functions_count);
    }
    void operator()(const NamedVariableDescription &m)
    {
        out.u16(m.variable.size);
        out.string(m.variable.name);
    }
    void operator()(const LocalEventDescription &m)
    {
        out.string(m.event.name);
        out.string(m.event.description);
    }
    void operator()(const NativeFunctionDescription &m)
    {
        out.string(m.function.name);
        out.string(m.function.description);
        out.u16(uint16_t(m.function.parameters.size()));
        for (const NativeParameter &parameter : m.function.parameters) {
            out.i16(parameter.size);
            out.string(parameter.name);
        }
    }
    void operator()(const Disconnected &) {}
    void operator()(const Variables &m)
    {
        out.u16(m.start);
        write_words(out, m.values);
    }
    void operator()(const ArrayAccessOutOfBounds &m)
    {
        out.u16(m.pc);
        out.u16(m.size);
        out.u16(m.index);
    }
    void operator()(const DivisionByZero &m)
    {
        out.u16(m.pc);
    }
    void operator()(const EventExecutionKilled &m)
    {
        out.u16(m.pc);
    }
    void operator()(const NodeSpecificError &m)
    {
        out.u16(m.pc);
        out.string(m.message);
    }
    void operator()(const ExecutionStateChanged &m)
    {
        out.u16(m.pc);
        out.u16(m.flags);
    }
    void operator()(const BreakpointSetResult &m)
    {
        out.u16(m.pc);
        out.u16(m.success);
    }
    void operator()(const NodePresent &m)
    {
        out.u16(m.version);
    }
    void operator()(const BootloaderDescription &m)
    {
        out.u16(m.page_size);
        out.u16(m.pages_start);
        out.u16(m.pages_count);
    }
    void operator()(const BootloaderPageDataRead &m)
    {
        for (uint8_t byte : m.data)
            out.byte(byte);
    }
    void operator()(const BootloaderAck &m)
    {
        out.u16(m.error_code);
        bool has_address = m.error_code == BOOTLOADER_ERROR_PROGRAMMING_FAILED;
        if (has_address != m.error_address.has_value())
            throw ProtocolError("BOOTLOADER_ACK carries an error address exactly when its code "
                                "is 2 (programming failed)");
        if (m.error_address)
            out.u16(*m.error_address);
    }
    void operator()(const GetDescription &m)
    {
        out.u16(m.version);
    }
    void operator()(const ListNodes &m)
    {
        out.u16(m.version);
    }
    void operator()(const NodeCommand &m)
    {
        require_type(is_dest_only(m.type), m.type, "NodeCommand");
        out.u16(m.dest);
    }
    void operator()(const SetBytecode &m)
    {
        out.u16(m.dest);
        out.u16(m.start);
        for (uint16_t word : m.words)
            out.u16(word);
    }
    void operator()(const BreakpointCommand &m)
    {
        require_type(m.type == NODE_MSG_BREAKPOINT_SET || m.type == NODE_MSG_BREAKPOINT_CLEAR,
                     m.type,
                     "BreakpointCommand");
        out.u16(m.dest);
        out.u16(m.pc);
    }
    void operator()(const GetVariables &m)
    {
        out.u16(m.dest);
        out.u16(m.start);
        out.u16(m.length);
    }
    void operator()(const SetVariables &m)
    {
        out.u16(m.dest);
        out.u16(m.start);
        write_words(out, m.values);
    }
    void operator()(const GetNodeDescription &m)
    {
        out.u16(m.dest);
        out.u16(m.version);
    }
    void operator()(const BootloaderPageCommand &m)
    {
        require_type(m.type == MSG_BOOTLOADER_READ_PAGE || m.type == MSG_BOOTLOADER_WRITE_PAGE,
                     m.type,
                     "BootloaderPageCommand");
        out.u16(m.dest);
        out.u16(m.page);
    }
    void operator()(const BootloaderPageDataWrite &m)
    {
        out.u16(m.dest);
        for (uint8_t byte : m.data)
            out.byte(byte);
    }
};

struct TypeOf {
    uint16_t operator()(const UserEvent &m) const
    {
        return m.id;
    }
    uint16_t operator()(const Description &) const
    {
        return NODE_MSG_DESCRIPTION;
    }
    uint16_t operator()(const NamedVariableDescription &) const
    {
        return NODE_MSG_NAMED_VARIABLE_DESCRIPTION;
    }
    uint16_t operator()(const LocalEventDescription &) const
    {
        return NODE_MSG_LOCAL_EVENT_DESCRIPTION;
    }
    uint16_t operator()(const NativeFunctionDescription &) const
    {
        return NODE_MSG_NATIVE_FUNCTION_DESCRIPTION;
    }
    uint16_t operator()(const Disconnected &) const
    {
        return NODE_MSG_DISCONNECTED;
    }
    uint16_t operator()(const Variables &) const
    {
        return NODE_MSG_VARIABLES;
    }
    uint16_t operator()(const ArrayAccessOutOfBounds &) const
    {
        return NODE_MSG_ARRAY_ACCESS_OUT_OF_BOUNDS;
    }
    uint16_t operator()(const DivisionByZero &) const
    {
        return NODE_MSG_DIVISION_BY_ZERO;
    }
    uint16_t operator()(const EventExecutionKilled &) const
    {
        return NODE_MSG_EVENT_EXECUTION_KILLED;
    }
    uint16_t operator()(const NodeSpecificError &) const
    {
        return NODE_MSG_NODE_SPECIFIC_ERROR;
    }
    uint16_t operator()(const ExecutionStateChanged &) const
    {
        return NODE_MSG_EXECUTION_STATE_CHANGED;
    }
    uint16_t operator()(const BreakpointSetResult &) const
    {
        return NODE_MSG_BREAKPOINT_SET_RESULT;
    }
    uint16_t operator()(const NodePresent &) const
    {
        return NODE_MSG_NODE_PRESENT;
    }
    uint16_t operator()(const BootloaderDescription &) const
    {
        return MSG_BOOTLOADER_DESCRIPTION;
    }
    uint16_t operator()(const BootloaderPageDataRead &) const
    {
        return MSG_BOOTLOADER_PAGE_DATA_READ;
    }
    uint16_t operator()(const BootloaderAck &) const
    {
        return MSG_BOOTLOADER_ACK;
    }
    uint16_t operator()(const GetDescription &) const
    {
        return NODE_MSG_GET_DESCRIPTION;
    }
    uint16_t operator()(const ListNodes &) const
    {
        return NODE_MSG_LIST_NODES;
    }
    uint16_t operator()(const NodeCommand &m) const
    {
        return m.type;
    }
    uint16_t operator()(const SetBytecode &) const
    {
        return NODE_MSG_SET_BYTECODE;
    }
    uint16_t operator()(const BreakpointCommand &m) const
    {
        return m.type;
    }
    uint16_t operator()(const GetVariables &) const
    {
        return NODE_MSG_GET_VARIABLES;
    }
    uint16_t operator()(const SetVariables &) const
    {
        return NODE_MSG_SET_VARIABLES;
    }
    uint16_t operator()(const GetNodeDescription &) const
    {
        return NODE_MSG_GET_NODE_DESCRIPTION;
    }
    uint16_t operator()(const BootloaderPageCommand &m) const
    {
        return m.type;
    }
    uint16_t operator()(const BootloaderPageDataWrite &) const
    {
        return MSG_BOOTLOADER_PAGE_DATA_WRITE;
    }
};

std::array<uint8_t, BOOTLOADER_DATA_CHUNK> read_chunk(PayloadReader &in)
{
    std::array<uint8_t, BOOTLOADER_DATA_CHUNK> data{};
    for (uint8_t &byte : data)
        byte = in.byte();
    return data;
}

Message decode_system(uint16_t type, PayloadReader &in, const char *name)
{
    switch (type) {
    case NODE_MSG_DESCRIPTION: {
        Description m;
        m.name = in.string();
        m.protocol_version = in.u16();
        m.bytecode_size = in.u16();
        m.stack_size = in.u16();
        m.variables_size = in.u16();
        m.named_variables_count = in.u16();
        m.local_events_count = in.u16();
        m.native_functions_count = in.u16();
        return m;
    }
    case NODE_MSG_NAMED_VARIABLE_DESCRIPTION: {
        NamedVariableDescription m;
        m.variable.size = in.u16();
        m.variable.name = in.string();
        return m;
    }
    case NODE_MSG_LOCAL_EVENT_DESCRIPTION: {
        LocalEventDescription m;
        m.event.name = in.string();
        m.event.description = in.string();
        return m;
    }
    case NODE_MSG_NATIVE_FUNCTION_DESCRIPTION: {
        NativeFunctionDescription m;
        m.function.name = in.string();
        m.function.description = in.string();
        uint16_t count = in.u16();
        for (uint16_t i = 0; i < count; i++) {
            NativeParameter parameter;
            parameter.size = in.i16();
            parameter.name = in.string();
            m.function.parameters.push_back(std::move(parameter));
        }
        return m;
    }
    case NODE_MSG_DISCONNECTED: return Disconnected{};
    case NODE_MSG_VARIABLES: {
        Variables m;
        m.start = in.u16();
        m.values = read_words(in, name);
        return m;
    }
    case NODE_MSG_ARRAY_ACCESS_OUT_OF_BOUNDS: {
        ArrayAccessOutOfBounds m;
        m.pc = in.u16();
        m.size = in.u16();
        m.index = in.u16();
        return m;
    }
    case NODE_MSG_DIVISION_BY_ZERO: return DivisionByZero{ in.u16() };
    case NODE_MSG_EVENT_EXECUTION_KILLED: return EventExecutionKilled{ in.u16() };
    case NODE_MSG_NODE_SPECIFIC_ERROR: {
        NodeSpecificError m;
        m.pc = in.u16();
        m.message = in.string();
        return m;
    }
    case NODE_MSG_EXECUTION_STATE_CHANGED: {
        ExecutionStateChanged m;
        m.pc = in.u16();
        m.flags = in.u16();
        return m;
    }
    case NODE_MSG_BREAKPOINT_SET_RESULT: {
        BreakpointSetResult m;
        m.pc = in.u16();
        m.success = in.u16();
        return m;
    }
    case NODE_MSG_NODE_PRESENT: return NodePresent{ in.u16() };
    case MSG_BOOTLOADER_DESCRIPTION: {
        BootloaderDescription m;
        m.page_size = in.u16();
        m.pages_start = in.u16();
        m.pages_count = in.u16();
        return m;
    }
    case MSG_BOOTLOADER_PAGE_DATA_READ: return BootloaderPageDataRead{ read_chunk(in) };
    case MSG_BOOTLOADER_ACK: {
        BootloaderAck m;
        m.error_code = in.u16();
        if (m.error_code == BOOTLOADER_ERROR_PROGRAMMING_FAILED)
            m.error_address = in.u16();
        return m;
    }
    case NODE_MSG_GET_DESCRIPTION: return GetDescription{ in.u16() };
    case NODE_MSG_LIST_NODES: return ListNodes{ in.u16() };
    case NODE_MSG_SET_BYTECODE: {
        SetBytecode m;
        m.dest = in.u16();
        m.start = in.u16();
        for (int16_t word : read_words(in, name))
            m.words.push_back(uint16_t(word));
        return m;
    }
    case NODE_MSG_BREAKPOINT_SET:
    case NODE_MSG_BREAKPOINT_CLEAR: {
        BreakpointCommand m;
        m.type = type;
        m.dest = in.u16();
        m.pc = in.u16();
        return m;
    }
    case NODE_MSG_GET_VARIABLES: {
        GetVariables m;
        m.dest = in.u16();
        m.start = in.u16();
        m.length = in.u16();
        return m;
    }
    case NODE_MSG_SET_VARIABLES: {
        SetVariables m;
        m.dest = in.u16();
        m.start = in.u16();
        m.values = read_words(in, name);
        return m;
    }
    case NODE_MSG_GET_NODE_DESCRIPTION: {
        GetNodeDescription m;
        m.dest = in.u16();
        m.version = in.u16();
        return m;
    }
    case MSG_BOOTLOADER_READ_PAGE:
    case MSG_BOOTLOADER_WRITE_PAGE: {
        BootloaderPageCommand m;
        m.type = type;
        m.dest = in.u16();
        m.page = in.u16();
        return m;
    }
    case MSG_BOOTLOADER_PAGE_DATA_WRITE: {
        BootloaderPageDataWrite m;
        m.dest = in.u16();
        m.data = read_chunk(in);
        return m;
    }
    default:
        if (is_dest_only(type))
            return NodeCommand{ type, in.u16() };
        throw ProtocolError(message_type_name(type) + " is not a protocol-5 message");
    }
}

} // namespace

uint16_t message_type(const Message &message)
{
    return std::visit(TypeOf{}, message);
}

Frame encode(const Message &message, uint16_t source)
{
    uint16_t type = message_type(message);
    if (std::holds_alternative<UserEvent>(message) && type >= FIRST_SYSTEM_TYPE)
        throw ProtocolError("user event id " + std::to_string(type) +
                            " is in the system range (ids are below 0x8000)");
    PayloadWriter writer;
    std::visit(Encoder{ writer }, message);
    Frame frame;
    frame.source = source;
    frame.type = type;
    frame.payload = writer.take();
    if (frame.payload.size() > MAX_PAYLOAD_SIZE)
        throw ProtocolError(
          message_type_name(type) + " of " + std::to_string(frame.payload.size()) +
          " payload bytes is longer than the protocol's " + std::to_string(MAX_PAYLOAD_SIZE));
    return frame;
}

Message decode(const Frame &frame)
{
    if (frame.payload.size() > MAX_PAYLOAD_SIZE)
        throw ProtocolError("payload of " + std::to_string(frame.payload.size()) +
                            " bytes is longer than the protocol's " +
                            std::to_string(MAX_PAYLOAD_SIZE));
    std::string name = message_type_name(frame.type);
    PayloadReader in(frame.payload, name.c_str());
    if (frame.type < FIRST_SYSTEM_TYPE) {
        UserEvent event;
        event.id = frame.type;
        event.arguments = read_words(in, name.c_str());
        return event;
    }
    Message message = decode_system(frame.type, in, name.c_str());
    in.expect_end();
    return message;
}

std::string message_type_name(uint16_t type)
{
    if (type < FIRST_SYSTEM_TYPE)
        return "user event " + std::to_string(type);
    if (const char *name = known_type_name(type))
        return name;
    char hex[8];
    std::snprintf(hex, sizeof hex, "%04X", unsigned(type));
    return std::string("unknown type 0x") + hex;
}

} // namespace aseba::client
