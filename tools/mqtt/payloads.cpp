// JSON payloads over nlohmann-json; every field read is checked for its type
// and range, and parse errors never throw past read_*.

#include "payloads.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace aseba::mqtt
{

using nlohmann::json;

namespace
{

constexpr size_t MAX_TEXT_FIELD = 128; // network names, bridge sessions
constexpr unsigned MAX_NESTING = 16;   // what any payload of docs/mqtt.md needs, with room

// The deepest nesting of arrays and objects, counted without parsing: a
// payload of a hundred thousand '[' must not reach the parser's or the
// printer's recursion.
unsigned nesting_depth(std::string_view text)
{
    unsigned depth = 0, deepest = 0;
    bool in_string = false, escaped = false;
    for (char c : text) {
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

json parse(std::string_view payload)
{
    if (nesting_depth(payload) > MAX_NESTING)
        throw PayloadError("the payload nests arrays or objects more than " +
                           std::to_string(MAX_NESTING) + " deep");
    json document = json::parse(payload, nullptr, false);
    if (document.is_discarded())
        throw PayloadError("the payload is not JSON");
    return document;
}

// Text for the broker; bytes that are not UTF-8 (a node name) become U+FFFD.
std::string text_of(const json &document)
{
    return document.dump(-1, ' ', false, json::error_handler_t::replace);
}

// A value for a log line: its JSON, cut short.
std::string shown(const json &value)
{
    std::string text = text_of(value);
    return text.size() > 40 ? text.substr(0, 37) + "..." : text;
}

std::vector<int16_t> read_arguments(const json &array, size_t max_arguments)
{
    if (!array.is_array())
        throw PayloadError("\"args\" must be an array of integers");
    if (array.size() > max_arguments)
        throw PayloadError(std::to_string(array.size()) + " arguments, more than the " +
                           std::to_string(max_arguments) + " the robots take");
    std::vector<int16_t> arguments;
    for (const json &value : array) {
        if (!value.is_number_integer())
            throw PayloadError("argument " + std::to_string(arguments.size()) + " (" +
                               shown(value) + ") is not an integer");
        int64_t number = value.get<int64_t>();
        if (value.is_number_unsigned() && value.get<uint64_t>() > uint64_t(INT64_MAX))
            number = INT64_MAX;
        if (number < -32768 || number > 32767)
            throw PayloadError("argument " + std::to_string(arguments.size()) + " (" +
                               shown(value) + ") is outside -32768..32767");
        arguments.push_back(int16_t(number));
    }
    return arguments;
}

std::string read_text(const json &object, const char *field)
{
    auto found = object.find(field);
    if (found == object.end() || !found->is_string() ||
        found->get_ref<const std::string &>().size() > MAX_TEXT_FIELD)
        throw PayloadError(std::string("\"") + field + "\" must be a short string");
    return found->get<std::string>();
}

uint64_t read_unsigned(const json &object, const char *field, uint64_t max)
{
    auto found = object.find(field);
    if (found == object.end() || !found->is_number_unsigned() || found->get<uint64_t>() > max)
        throw PayloadError(std::string("\"") + field + "\" must be an integer from 0 to " +
                           std::to_string(max));
    return found->get<uint64_t>();
}

} // namespace

std::string write_event(const std::vector<int16_t> &arguments,
                        const EventOrigin &origin,
                        const std::string &node_name,
                        int64_t time_ms)
{
    json document = { { "args", arguments },     { "network", origin.network },
                      { "node", origin.node },   { "node_name", node_name },
                      { "time_ms", time_ms },    { "bridge", origin.bridge },
                      { "seq", origin.sequence } };
    return text_of(document);
}

EventPayload read_event(std::string_view payload, size_t max_arguments)
{
    EventPayload event;
    if (payload.find_first_not_of(" \t\r\n") == std::string_view::npos)
        return event;
    json document = parse(payload);
    if (document.is_array()) {
        event.arguments = read_arguments(document, max_arguments);
        return event;
    }
    if (!document.is_object())
        throw PayloadError("the payload must be a JSON object with \"args\", or an array");
    if (auto args = document.find("args"); args != document.end())
        event.arguments = read_arguments(*args, max_arguments);
    // Published by a bridge: every field of the origin must be there.
    if (document.contains("bridge")) {
        EventOrigin origin;
        origin.bridge = read_text(document, "bridge");
        origin.sequence = read_unsigned(document, "seq", UINT64_MAX);
        origin.network = read_text(document, "network");
        origin.node = uint16_t(read_unsigned(document, "node", UINT16_MAX));
        event.origin = origin;
    }
    return event;
}

std::string write_node(const std::string &network, const client::Node &node)
{
    json document = { { "network", network },
                      { "node", node.key.id },
                      { "name", node.described ? node.description.name : "" },
                      { "protocol", node.protocol_version },
                      { "described", node.described } };
    if (node.execution)
        document["state"] = node.execution->name();
    if (node.described) {
        const TargetDescription &description = node.description;
        document["bytecode_size"] = description.bytecode_size;
        document["stack_size"] = description.stack_size;
        document["variables_size"] = description.variables_size;
        json variables = json::array();
        for (const NamedVariable &variable : description.named_variables)
            variables.push_back({ { "name", variable.name }, { "size", variable.size } });
        document["variables"] = variables;
        json events = json::array();
        for (const LocalEvent &event : description.local_events)
            events.push_back({ { "name", event.name }, { "description", event.description } });
        document["local_events"] = events;
        json natives = json::array();
        for (const NativeFunction &function : description.native_functions)
            natives.push_back(function.name);
        document["native_functions"] = natives;
    }
    return text_of(document);
}

std::string write_status(bool online,
                         const std::string &bridge,
                         const std::vector<std::string> &networks)
{
    return text_of(json{ { "online", online }, { "bridge", bridge }, { "networks", networks } });
}

std::string write_values(const std::vector<int16_t> &values)
{
    return text_of(json(values));
}

const char *command_name(CommandKind kind)
{
    switch (kind) {
    case CommandKind::load: return "load";
    case CommandKind::run: return "run";
    case CommandKind::pause: return "pause";
    case CommandKind::stop: return "stop";
    case CommandKind::reset: return "reset";
    case CommandKind::reboot: return "reboot";
    }
    return "?";
}

Command read_command(std::string_view payload)
{
    json document = parse(payload);
    if (!document.is_object())
        throw PayloadError("a command must be a JSON object with \"command\"");
    Command command;
    if (auto request = document.find("request"); request != document.end())
        command.request = text_of(*request);
    auto name = document.find("command");
    if (name == document.end() || !name->is_string())
        throw PayloadError("\"command\" must be one of load, run, pause, stop, reset, reboot");
    bool known = false;
    for (CommandKind kind : { CommandKind::load,
                              CommandKind::run,
                              CommandKind::pause,
                              CommandKind::stop,
                              CommandKind::reset,
                              CommandKind::reboot })
        if (*name == command_name(kind)) {
            command.kind = kind;
            known = true;
        }
    if (!known)
        throw PayloadError("unknown command " + shown(*name) +
                           " (load, run, pause, stop, reset or reboot)");
    if (command.kind == CommandKind::load) {
        auto program = document.find("program");
        if (program == document.end() || !program->is_string())
            throw PayloadError("load needs \"program\": the text of an .aesl project or a script");
        command.program = program->get<std::string>();
    }
    return command;
}

std::string write_reply(const Reply &reply)
{
    json document = { { "command", reply.command }, { "node", reply.node }, { "ok", reply.ok } };
    if (!reply.request.empty())
        document["request"] = json::parse(reply.request, nullptr, false);
    if (!reply.state.empty())
        document["state"] = reply.state;
    if (!reply.error.empty())
        document["error"] = reply.error;
    return text_of(document);
}

} // namespace aseba::mqtt
