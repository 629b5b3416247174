// Browser requests from JSON, with every value checked.

#include "requests.hpp"

#include <array>
#include <cctype>
#include <limits>
#include <set>

#include <nlohmann/json.hpp>

namespace aseba::ide
{

namespace
{

using Json = nlohmann::json;

constexpr std::array ACTIONS{
    std::pair{ Action::run, "run" },      std::pair{ Action::pause, "pause" },
    std::pair{ Action::step, "step" },    std::pair{ Action::stop, "stop" },
    std::pair{ Action::reset, "reset" },  std::pair{ Action::store, "store" },
    std::pair{ Action::reboot, "reboot" }
};

// A program line or index is never near this; it keeps sizes sane.
constexpr uint64_t MAX_INDEX = 65535;
constexpr size_t MAX_ROBOTS = 4096;

const Json &field(const Json &object, const char *name)
{
    auto found = object.find(name);
    if (found == object.end())
        throw RequestError(std::string("'") + name + "' is missing");
    return *found;
}

std::string text_field(const Json &object, const char *name, size_t max_bytes)
{
    const Json &value = field(object, name);
    if (!value.is_string())
        throw RequestError(std::string("'") + name + "' must be a string");
    const std::string &text = value.get_ref<const std::string &>();
    if (text.size() > max_bytes)
        throw RequestError(std::string("'") + name + "' is too long (" +
                           std::to_string(text.size()) + " bytes, at most " +
                           std::to_string(max_bytes) + ")");
    return text;
}

uint64_t unsigned_value(const Json &value, const char *what, uint64_t max)
{
    // nlohmann-json reads every integer without a sign as unsigned.
    if (!value.is_number_unsigned() || value.get<uint64_t>() > max)
        throw RequestError(std::string(what) + " must be a whole number from 0 to " +
                           std::to_string(max));
    return value.get<uint64_t>();
}

int16_t word_value(const Json &value, const char *what)
{
    bool in_range =
      value.is_number_unsigned()
        ? value.get<uint64_t>() <= uint64_t(std::numeric_limits<int16_t>::max())
        : value.is_number_integer() && value.get<int64_t>() >= std::numeric_limits<int16_t>::min();
    if (!in_range)
        throw RequestError(std::string(what) + " must be whole numbers from -32768 to 32767 (" +
                           value.dump() + " is not)");
    return int16_t(value.get<int64_t>());
}

std::vector<int16_t> words_field(const Json &object, const char *name)
{
    const Json &list = field(object, name);
    if (!list.is_array() || list.size() > MAX_EVENT_WORDS)
        throw RequestError(std::string("'") + name + "' must be a list of at most " +
                           std::to_string(MAX_EVENT_WORDS) + " numbers");
    std::vector<int16_t> words;
    for (const Json &value : list)
        words.push_back(word_value(value, name));
    return words;
}

NodeKey robot_value(const Json &value)
{
    if (!value.is_string())
        throw RequestError("a robot is named \"TARGET:ID\"");
    const std::string &text = value.get_ref<const std::string &>();
    size_t colon = text.find(':');
    auto number = [&](std::string_view part, uint64_t max) {
        if (part.empty() || part.size() > 5 ||
            part.find_first_not_of("0123456789") != std::string_view::npos ||
            std::stoull(std::string(part)) > max)
            throw RequestError("'" + text + "' is not a robot (\"TARGET:ID\")");
        return std::stoull(std::string(part));
    };
    if (colon == std::string::npos)
        throw RequestError("'" + text + "' is not a robot (\"TARGET:ID\")");
    NodeKey key;
    key.target = size_t(number(std::string_view(text).substr(0, colon), MAX_ROBOTS));
    key.id = uint16_t(number(std::string_view(text).substr(colon + 1), 65535));
    return key;
}

std::vector<NodeKey> robots_field(const Json &object, const char *name)
{
    const Json &list = field(object, name);
    if (!list.is_array() || list.size() > MAX_ROBOTS)
        throw RequestError(std::string("'") + name + "' must be a list of robots");
    std::vector<NodeKey> robots;
    std::set<NodeKey> seen;
    for (const Json &value : list) {
        NodeKey key = robot_value(value);
        if (seen.insert(key).second)
            robots.push_back(key);
    }
    return robots;
}

std::vector<unsigned> lines_field(const Json &object, const char *name)
{
    auto found = object.find(name);
    if (found == object.end())
        return {};
    if (!found->is_array() || found->size() > MAX_INDEX)
        throw RequestError(std::string("'") + name + "' must be a list of line numbers");
    std::set<unsigned> lines;
    for (const Json &value : *found) {
        unsigned line = unsigned(unsigned_value(value, "a line number", MAX_INDEX));
        if (line == 0)
            throw RequestError("line numbers start at 1");
        lines.insert(line);
    }
    return { lines.begin(), lines.end() };
}

bool bool_field(const Json &object, const char *name, bool otherwise)
{
    auto found = object.find(name);
    if (found == object.end())
        return otherwise;
    if (!found->is_boolean())
        throw RequestError(std::string("'") + name + "' must be true or false");
    return found->get<bool>();
}

// language.md §2.3 (ASCII part; letters beyond ASCII are the compiler's to
// judge): a letter or '_', then letters, digits, '_' and '.'.
void check_identifier(const std::string &name, const char *what)
{
    bool ok =
      !name.empty() && name.size() <= 64 && !(name[0] >= '0' && name[0] <= '9') && name[0] != '.';
    for (unsigned char c : name)
        ok = ok && (c >= 0x80 || std::isalnum(c) || c == '_' || c == '.');
    if (!ok)
        throw RequestError(
          std::string(what) + " '" + name +
          "' is not a name (letters, digits, '_' and '.', not starting with a digit)");
}

CommonDefinitions definitions_value(const Json &object)
{
    CommonDefinitions definitions;
    std::set<std::string> names;
    const Json &events = field(object, "events");
    const Json &constants = field(object, "constants");
    if (!events.is_array() || !constants.is_array() ||
        events.size() + constants.size() > MAX_DEFINITIONS)
        throw RequestError("'events' and 'constants' must be lists of at most " +
                           std::to_string(MAX_DEFINITIONS) + " definitions");
    for (const Json &event : events) {
        if (!event.is_object())
            throw RequestError("an event is {\"name\": ..., \"size\": ...}");
        GlobalEvent definition;
        definition.name = text_field(event, "name", 64);
        check_identifier(definition.name, "event");
        definition.size =
          uint16_t(unsigned_value(field(event, "size"), "an event's size", MAX_EVENT_WORDS));
        if (!names.insert(definition.name).second)
            throw RequestError("'" + definition.name + "' is declared twice");
        definitions.events.push_back(definition);
    }
    for (const Json &constant : constants) {
        if (!constant.is_object())
            throw RequestError("a constant is {\"name\": ..., \"value\": ...}");
        Constant definition;
        definition.name = text_field(constant, "name", 64);
        check_identifier(definition.name, "constant");
        definition.value = word_value(field(constant, "value"), "constant values");
        if (!names.insert(definition.name).second)
            throw RequestError("'" + definition.name + "' is declared twice");
        definitions.constants.push_back(definition);
    }
    return definitions;
}

Action action_value(const Json &value)
{
    if (value.is_string())
        for (const auto &[action, name] : ACTIONS)
            if (value.get_ref<const std::string &>() == name)
                return action;
    throw RequestError("'action' must be one of run, pause, step, stop, reset, store, reboot");
}

Request request_of_type(const std::string &type, const Json &message)
{
    if (type == "compile")
        return CompileRequest{ robot_value(field(message, "robot")),
                               text_field(message, "source", MAX_SCRIPT_BYTES),
                               bool_field(message, "remember", true) };
    if (type == "script")
        return ScriptRequest{ robot_value(field(message, "robot")),
                              text_field(message, "source", MAX_SCRIPT_BYTES) };
    if (type == "bytecode")
        return BytecodeRequest{ robot_value(field(message, "robot")),
                                text_field(message, "source", MAX_SCRIPT_BYTES) };
    if (type == "load") {
        LoadRequest load;
        const Json &programs = field(message, "programs");
        if (!programs.is_array() || programs.empty() || programs.size() > MAX_ROBOTS)
            throw RequestError("'programs' must be a non-empty list");
        std::set<NodeKey> seen;
        for (const Json &program : programs) {
            if (!program.is_object())
                throw RequestError("a program is {\"robot\": ..., \"source\": ...}");
            LoadRequest::Program entry{ robot_value(field(program, "robot")),
                                        text_field(program, "source", MAX_SCRIPT_BYTES),
                                        lines_field(program, "breakpoints") };
            if (!seen.insert(entry.robot).second)
                throw RequestError("robot " + robot_name(entry.robot) + " is given two programs");
            load.programs.push_back(std::move(entry));
        }
        load.run = bool_field(message, "run", true);
        return load;
    }
    if (type == "control")
        return ControlRequest{ robots_field(message, "robots"),
                               action_value(field(message, "action")) };
    if (type == "breakpoints")
        return BreakpointsRequest{ robot_value(field(message, "robot")),
                                   lines_field(message, "lines") };
    if (type == "set-variable") {
        SetVariableRequest set;
        set.robot = robot_value(field(message, "robot"));
        set.name = text_field(message, "name", 256);
        if (auto index = message.find("index"); index != message.end())
            set.index = unsigned(unsigned_value(*index, "'index'", MAX_INDEX));
        set.values = words_field(message, "values");
        if (set.values.empty())
            throw RequestError("'values' is empty");
        return set;
    }
    if (type == "emit")
        return EmitRequest{ text_field(message, "event", 64), words_field(message, "args") };
    if (type == "definitions")
        return DefinitionsRequest{ definitions_value(message) };
    if (type == "watch")
        return WatchRequest{ robots_field(message, "robots") };
    if (type == "open-project")
        return OpenProjectRequest{ text_field(message, "name", 4096),
                                   text_field(message, "content", MAX_PROJECT_BYTES) };
    if (type == "save-project")
        return SaveProjectRequest{ bool_field(message, "toServerFile", false) };
    throw RequestError("unknown request type '" + type + "'");
}

} // namespace

std::string robot_name(NodeKey key)
{
    return std::to_string(key.target) + ":" + std::to_string(key.id);
}

const char *action_name(Action action)
{
    for (const auto &[known, name] : ACTIONS)
        if (known == action)
            return name;
    return "?";
}

ParsedRequest parse_request(std::string_view text)
{
    Json message = Json::parse(text, nullptr, false);
    if (message.is_discarded())
        throw RequestError("the message is not JSON");
    if (!message.is_object())
        throw RequestError("the message is not a JSON object");
    ParsedRequest parsed;
    if (auto id = message.find("id"); id != message.end())
        parsed.id = unsigned_value(*id, "'id'", uint64_t(1) << 53);
    const Json &type = field(message, "type");
    if (!type.is_string())
        throw RequestError("'type' must be a string");
    parsed.request = request_of_type(type.get<std::string>(), message);
    return parsed;
}

uint64_t request_id_of(std::string_view text)
{
    Json message = Json::parse(text, nullptr, false);
    if (!message.is_object())
        return 0;
    auto id = message.find("id");
    if (id == message.end() || !id->is_number_unsigned())
        return 0;
    return id->get<uint64_t>();
}

} // namespace aseba::ide
