// Target descriptions in JSON (docs/target-description.md) over
// nlohmann-json: its parser is iterative, so no nesting can exhaust the
// stack; here, only the mapping onto TargetDescription and its checks.
// Everything is linear in the size of the file: the nesting is measured
// before parsing rather than by nlohmann's parser callback, which scans the
// array so far at the end of each of its objects (quadratic in the number of
// local events), and the counts the bytecode limits are checked before any
// item is read.

#include "target_json.hpp"

#include <optional>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "target_presets.hpp"

namespace aseba
{

namespace
{

using Json = nlohmann::json;

constexpr int MAX_JSON_DEPTH = 64; // a description nests 4 levels deep
constexpr long long WORD_LIMIT = 0xFFFF;
constexpr long long PARAMETER_SIZE_MIN = -32768;
constexpr long long PARAMETER_SIZE_MAX = 32767;

// A value that is not what the format says, named by its path in the file
// (`natives[3].parameters[0].size`).
struct DescriptionError : std::runtime_error {
    DescriptionError(const std::string &path, const std::string &message)
      : std::runtime_error(path.empty() ? message : path + ": " + message)
    {
    }
};

std::string member_path(const std::string &object, const std::string &key)
{
    return object.empty() ? key : object + "." + key;
}

std::string item_path(const std::string &array, size_t index)
{
    return array + "[" + std::to_string(index) + "]";
}

const Json &object_at(const Json &value, const std::string &path)
{
    if (!value.is_object())
        throw DescriptionError(path, "expected an object");
    return value;
}

const Json *member(const Json &object, const std::string &key)
{
    auto found = object.find(key);
    return found == object.end() ? nullptr : &*found;
}

long long integer(const Json &object,
                  const std::string &path,
                  const std::string &key,
                  long long low,
                  long long high,
                  std::optional<long long> fallback = std::nullopt)
{
    const Json *value = member(object, key);
    std::string where = member_path(path, key);
    if (value == nullptr) {
        if (fallback)
            return *fallback;
        throw DescriptionError(where, "missing");
    }
    // Unsigned numbers above the signed range are out of range anyway.
    if (!value->is_number_integer())
        throw DescriptionError(where, "must be an integer");
    long long number = value->is_number_unsigned() && value->get<unsigned long long>() > WORD_LIMIT
                         ? high + 1
                         : value->get<long long>();
    if (number < low || number > high)
        throw DescriptionError(where,
                               "must be in [" + std::to_string(low) + ", " + std::to_string(high) +
                                 "], not " + value->dump());
    return number;
}

std::string text(const Json &object,
                 const std::string &path,
                 const std::string &key,
                 bool optional = false)
{
    const Json *value = member(object, key);
    std::string where = member_path(path, key);
    if (value == nullptr) {
        if (optional)
            return "";
        throw DescriptionError(where, "missing");
    }
    if (!value->is_string())
        throw DescriptionError(where, "must be a string");
    return value->get<std::string>();
}

std::string name_member(const Json &object, const std::string &path)
{
    std::string name = text(object, path, "name");
    if (name.empty())
        throw DescriptionError(member_path(path, "name"), "must not be empty");
    return name;
}

// The items of an optional array member (none when absent).
const Json &array_member(const Json &object, const std::string &path, const std::string &key)
{
    static const Json none = Json::array();
    const Json *value = member(object, key);
    if (value == nullptr)
        return none;
    if (!value->is_array())
        throw DescriptionError(member_path(path, key), "must be an array");
    return *value;
}

// Names the compiler looks up must be unique within their kind.
template<typename Item>
void check_unique(const std::vector<Item> &items, const std::string &array)
{
    std::set<std::string> seen;
    for (size_t i = 0; i < items.size(); i++)
        if (!seen.insert(items[i].name).second)
            throw DescriptionError(item_path(array, i),
                                   "the name " + items[i].name + " is used twice");
}

// "standard" in the natives: the standard natives, in their order.
bool is_standard_shorthand(const Json &native)
{
    return native.is_string() && native.get_ref<const std::string &>() == "standard";
}

NativeFunction native_from(const Json &value, const std::string &path)
{
    object_at(value, path);
    NativeFunction function;
    function.name = name_member(value, path);
    function.description = text(value, path, "description", true);
    const std::string parameters_path = member_path(path, "parameters");
    const Json &parameters = array_member(value, path, "parameters");
    for (size_t i = 0; i < parameters.size(); i++) {
        std::string where = item_path(parameters_path, i);
        object_at(parameters[i], where);
        function.parameters.push_back(
          { name_member(parameters[i], where),
            static_cast<int16_t>(
              integer(parameters[i], where, "size", PARAMETER_SIZE_MIN, PARAMETER_SIZE_MAX)) });
    }
    return function;
}

TargetDescription target_from(const Json &root)
{
    object_at(root, "");
    TargetDescription target;
    target.name = name_member(root, "");
    target.protocol_version =
      static_cast<uint16_t>(integer(root, "", "protocol_version", 0, WORD_LIMIT, 5));
    target.bytecode_size = static_cast<uint16_t>(integer(root, "", "bytecode_size", 1, WORD_LIMIT));
    target.variables_size =
      static_cast<uint16_t>(integer(root, "", "variables_size", 0, WORD_LIMIT));
    target.stack_size = static_cast<uint16_t>(integer(root, "", "stack_size", 1, WORD_LIMIT));

    const Json &variables = array_member(root, "", "variables");
    long long named_words = 0;
    for (size_t i = 0; i < variables.size(); i++) {
        std::string where = item_path("variables", i);
        object_at(variables[i], where);
        NamedVariable variable{ name_member(variables[i], where),
                                static_cast<uint16_t>(
                                  integer(variables[i], where, "size", 1, WORD_LIMIT, 1)) };
        named_words += variable.size;
        target.named_variables.push_back(variable);
    }
    if (named_words > target.variables_size)
        throw DescriptionError("variables",
                               "the named variables take " + std::to_string(named_words) +
                                 " words, more than variables_size (" +
                                 std::to_string(target.variables_size) + ")");
    check_unique(target.named_variables, "variables");

    const Json &events = array_member(root, "", "local_events");
    if (std::string error = local_events_limit_error(events.size()); !error.empty())
        throw DescriptionError("local_events", error);
    for (size_t i = 0; i < events.size(); i++) {
        std::string where = item_path("local_events", i);
        object_at(events[i], where);
        target.local_events.push_back(
          { name_member(events[i], where), text(events[i], where, "description", true) });
    }
    check_unique(target.local_events, "local_events");

    const Json &natives = array_member(root, "", "natives");
    const size_t standard_count = standard_native_functions().size();
    size_t native_count = 0;
    for (const Json &native : natives)
        native_count += is_standard_shorthand(native) ? standard_count : 1;
    if (std::string error = natives_limit_error(native_count); !error.empty())
        throw DescriptionError("natives", error);
    for (size_t i = 0; i < natives.size(); i++) {
        if (is_standard_shorthand(natives[i])) {
            for (const NativeFunction &function : standard_native_functions())
                target.native_functions.push_back(function);
            continue;
        }
        target.native_functions.push_back(native_from(natives[i], item_path("natives", i)));
    }
    check_unique(target.native_functions, "natives");
    return target;
}

// Whether `text` nests arrays and objects more than MAX_JSON_DEPTH deep
// (brackets inside strings do not count); malformed text is left to the
// parser.
bool nested_too_deeply(std::string_view text)
{
    int depth = 0;
    bool in_string = false;
    for (size_t i = 0; i < text.size(); i++) {
        char c = text[i];
        if (in_string) {
            if (c == '\\')
                i++;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > MAX_JSON_DEPTH)
                return true;
        } else if (c == ']' || c == '}') {
            depth--;
        }
    }
    return false;
}

// nlohmann's message without its "[json.exception.KIND.ID] " prefix: "parse
// error at line L, column C: ...", "number overflow parsing '1e999'".
std::string json_error_text(const nlohmann::json::exception &error)
{
    std::string message = error.what();
    size_t end_of_prefix = message.find("] ");
    return end_of_prefix == std::string::npos ? message : message.substr(end_of_prefix + 2);
}

} // namespace

TargetReadResult read_target_json(std::string_view text_of_file)
{
    TargetReadResult result;
    try {
        // Refuses absurd nesting before any value is built.
        if (nested_too_deeply(text_of_file))
            throw DescriptionError(
              "", "nested more than " + std::to_string(MAX_JSON_DEPTH) + " levels deep");
        Json root = Json::parse(text_of_file.begin(), text_of_file.end());
        result.target = target_from(root);
        result.ok = true;
    } catch (const nlohmann::json::exception &error) {
        // Bad syntax, or a number out of every integer's range.
        result.error = json_error_text(error);
    } catch (const DescriptionError &error) {
        result.error = error.what();
    }
    return result;
}

std::string write_target_json(const TargetDescription &target)
{
    // In the format's order, which people read in.
    using OrderedJson = nlohmann::ordered_json;
    OrderedJson root;
    root["name"] = target.name;
    root["protocol_version"] = target.protocol_version;
    root["bytecode_size"] = target.bytecode_size;
    root["variables_size"] = target.variables_size;
    root["stack_size"] = target.stack_size;
    root["variables"] = OrderedJson::array();
    for (const NamedVariable &variable : target.named_variables)
        root["variables"].push_back({ { "name", variable.name }, { "size", variable.size } });
    root["local_events"] = OrderedJson::array();
    for (const LocalEvent &event : target.local_events)
        root["local_events"].push_back(
          { { "name", event.name }, { "description", event.description } });
    root["natives"] = OrderedJson::array();
    for (const NativeFunction &native : target.native_functions) {
        OrderedJson parameters = OrderedJson::array();
        for (const NativeParameter &parameter : native.parameters)
            parameters.push_back({ { "name", parameter.name }, { "size", parameter.size } });
        root["natives"].push_back({ { "name", native.name },
                                    { "description", native.description },
                                    { "parameters", parameters } });
    }
    // Names from a node may not be UTF-8: such bytes are replaced, not fatal.
    return root.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

} // namespace aseba
