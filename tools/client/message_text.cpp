// Text of messages for monitors and error reports.

#include "message_text.hpp"

#include <cstdio>
#include <ctime>

namespace aseba::client
{

namespace
{

std::string hex16(uint16_t value)
{
    char text[8];
    std::snprintf(text, sizeof text, "0x%04X", unsigned(value));
    return text;
}

std::string word_list(const std::vector<int16_t> &values)
{
    std::string text;
    for (size_t i = 0; i < values.size(); i++)
        text += (i == 0 ? "" : ", ") + std::to_string(values[i]);
    return text;
}

std::string at_pc(uint16_t pc, const CompiledProgram *program)
{
    std::string text = "at pc " + std::to_string(pc);
    if (program == nullptr)
        return text;
    unsigned line = source_line_of(*program, pc);
    if (line == 0)
        return text;
    return text + " (line " + std::to_string(line) + ": " + source_line_text(*program, line) + ")";
}

struct Describer {
    const CommonDefinitions *definitions;
    const CompiledProgram *program;

    std::string operator()(const UserEvent &m) const
    {
        return event_name(m.id, definitions) + "(" + word_list(m.arguments) + ")";
    }
    std::string operator()(const Description &m) const
    {
        return "DESCRIPTION " + m.name + " protocol " + std::to_string(m.protocol_version) +
               ", bytecode " + std::to_string(m.bytecode_size) + ", stack " +
               std::to_string(m.stack_size) + ", variables " + std::to_string(m.variables_size) +
               " words; " + std::to_string(m.named_variables_count) + " variables, " +
               std::to_string(m.local_events_count) + " local events, " +
               std::to_string(m.native_functions_count) + " native functions";
    }
    std::string operator()(const NamedVariableDescription &m) const
    {
        return "NAMED_VARIABLE_DESCRIPTION " + m.variable.name + "[" +
               std::to_string(m.variable.size) + "]";
    }
    std::string operator()(const LocalEventDescription &m) const
    {
        return "LOCAL_EVENT_DESCRIPTION " + m.event.name + ": " + m.event.description;
    }
    std::string operator()(const NativeFunctionDescription &m) const
    {
        std::string text = "NATIVE_FUNCTION_DESCRIPTION " + m.function.name + "(";
        for (size_t i = 0; i < m.function.parameters.size(); i++)
            text += (i == 0 ? "" : ", ") + m.function.parameters[i].name + "[" +
                    std::to_string(m.function.parameters[i].size) + "]";
        return text + ")";
    }
    std::string operator()(const Disconnected &) const
    {
        return "DISCONNECTED";
    }
    std::string operator()(const Variables &m) const
    {
        return "VARIABLES at " + std::to_string(m.start) + ": " + word_list(m.values);
    }
    std::string operator()(const ArrayAccessOutOfBounds &m) const
    {
        return "ARRAY_ACCESS_OUT_OF_BOUNDS " + at_pc(m.pc, program) + ": index " +
               std::to_string(int16_t(m.index)) + " of an array of size " + std::to_string(m.size);
    }
    std::string operator()(const DivisionByZero &m) const
    {
        return "DIVISION_BY_ZERO " + at_pc(m.pc, program);
    }
    std::string operator()(const EventExecutionKilled &m) const
    {
        return "EVENT_EXECUTION_KILLED " + at_pc(m.pc, program);
    }
    std::string operator()(const NodeSpecificError &m) const
    {
        return "NODE_SPECIFIC_ERROR " + at_pc(m.pc, program) + ": " + m.message;
    }
    std::string operator()(const ExecutionStateChanged &m) const
    {
        ExecutionState state{ m.pc, m.flags };
        return "EXECUTION_STATE_CHANGED " + state.name() + " " + at_pc(m.pc, program) + ", flags " +
               hex16(m.flags);
    }
    std::string operator()(const BreakpointSetResult &m) const
    {
        return "BREAKPOINT_SET_RESULT " + at_pc(m.pc, program) +
               (m.success ? ": set" : ": refused");
    }
    std::string operator()(const NodePresent &m) const
    {
        return "NODE_PRESENT protocol " + std::to_string(m.version);
    }
    std::string operator()(const BootloaderDescription &m) const
    {
        return "BOOTLOADER_DESCRIPTION page size " + std::to_string(m.page_size) + ", pages " +
               std::to_string(m.pages_start) + " + " + std::to_string(m.pages_count);
    }
    std::string operator()(const BootloaderPageDataRead &) const
    {
        return "BOOTLOADER_PAGE_DATA_READ";
    }
    std::string operator()(const BootloaderAck &m) const
    {
        std::string text = "BOOTLOADER_ACK error " + std::to_string(m.error_code);
        if (m.error_address)
            text += " at " + hex16(*m.error_address);
        return text;
    }
    std::string operator()(const GetDescription &m) const
    {
        return "GET_DESCRIPTION protocol " + std::to_string(m.version);
    }
    std::string operator()(const ListNodes &m) const
    {
        return "LIST_NODES protocol " + std::to_string(m.version);
    }
    std::string operator()(const NodeCommand &m) const
    {
        return message_type_name(m.type) + " to " + std::to_string(m.dest);
    }
    std::string operator()(const SetBytecode &m) const
    {
        return "SET_BYTECODE to " + std::to_string(m.dest) + ": " + std::to_string(m.words.size()) +
               " words at " + std::to_string(m.start);
    }
    std::string operator()(const BreakpointCommand &m) const
    {
        return message_type_name(m.type) + " to " + std::to_string(m.dest) + " at pc " +
               std::to_string(m.pc);
    }
    std::string operator()(const GetVariables &m) const
    {
        return "GET_VARIABLES to " + std::to_string(m.dest) + ": " + std::to_string(m.length) +
               " words at " + std::to_string(m.start);
    }
    std::string operator()(const SetVariables &m) const
    {
        return "SET_VARIABLES to " + std::to_string(m.dest) + " at " + std::to_string(m.start) +
               ": " + word_list(m.values);
    }
    std::string operator()(const GetNodeDescription &m) const
    {
        return "GET_NODE_DESCRIPTION to " + std::to_string(m.dest);
    }
    std::string operator()(const BootloaderPageCommand &m) const
    {
        return message_type_name(m.type) + " to " + std::to_string(m.dest) + " page " +
               std::to_string(m.page);
    }
    std::string operator()(const BootloaderPageDataWrite &m) const
    {
        return "BOOTLOADER_PAGE_DATA_WRITE to " + std::to_string(m.dest);
    }
};

} // namespace

std::string event_name(uint16_t id, const CommonDefinitions *definitions)
{
    if (definitions != nullptr && id < definitions->events.size())
        return "event " + definitions->events[id].name;
    return "event " + std::to_string(id);
}

std::string message_text(const Message &message,
                         const CommonDefinitions *definitions,
                         const CompiledProgram *program)
{
    return std::visit(Describer{ definitions, program }, message);
}

std::string timestamp_text(std::chrono::system_clock::time_point time)
{
    using namespace std::chrono;
    auto since_epoch = time.time_since_epoch();
    std::time_t seconds = std::time_t(duration_cast<std::chrono::seconds>(since_epoch).count());
    long milliseconds = long(duration_cast<std::chrono::milliseconds>(since_epoch).count() % 1000);
    std::tm parts{};
    gmtime_r(&seconds, &parts);
    char text[32];
    std::snprintf(text,
                  sizeof text,
                  "%02d:%02d:%02d.%03ld",
                  parts.tm_hour,
                  parts.tm_min,
                  parts.tm_sec,
                  milliseconds);
    return text;
}

} // namespace aseba::client
