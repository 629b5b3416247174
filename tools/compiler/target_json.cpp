// A minimal JSON reader (objects, arrays, strings, integers, booleans, null)
// and the mapping of docs/target-description.md onto TargetDescription.

#include "target_json.hpp"

#include <cstdio>
#include <map>
#include <optional>
#include <memory>
#include <stdexcept>
#include <vector>

#include "lexer.hpp"
#include "target_presets.hpp"

namespace aseba
{

namespace
{

constexpr unsigned MAX_JSON_DEPTH = 64;
constexpr long long WORD_LIMIT = 0xFFFF;
constexpr long long PARAMETER_SIZE_MIN = -32768;
constexpr long long PARAMETER_SIZE_MAX = 32767;

struct JsonError : std::runtime_error {
    JsonError(unsigned where, const std::string &message)
      : std::runtime_error("line " + std::to_string(where) + ": " + message)
    {
    }
};

struct JsonMember;

struct JsonValue {
    enum class Kind { Null, Boolean, Number, String, Array, Object } kind = Kind::Null;
    bool boolean = false;
    long long number = 0;
    std::string string;
    std::vector<JsonValue> array;
    // A vector may hold a type still incomplete here; a std::pair may not.
    std::vector<JsonMember> object; // in file order
    unsigned line = 0;

    const JsonValue *member(const std::string &key) const;
};

struct JsonMember {
    std::string name;
    JsonValue value;
};

const JsonValue *JsonValue::member(const std::string &key) const
{
    for (const auto &[name, value] : object)
        if (name == key)
            return &value;
    return nullptr;
}

class JsonParser
{
  public:
    explicit JsonParser(std::string_view document)
      : text(document)
    {
    }

    JsonValue parse()
    {
        JsonValue value = parse_value(0);
        skip_spaces();
        if (position != text.size())
            throw JsonError(line, "unexpected text after the JSON value");
        return value;
    }

  private:
    std::string_view text;
    size_t position = 0;
    unsigned line = 1;

    void skip_spaces()
    {
        while (position < text.size() && (text[position] == ' ' || text[position] == '\t' ||
                                          text[position] == '\n' || text[position] == '\r')) {
            if (text[position] == '\n')
                ++line;
            ++position;
        }
    }

    char peek()
    {
        skip_spaces();
        if (position >= text.size())
            throw JsonError(line, "unexpected end of the file");
        return text[position];
    }

    void expect(char c)
    {
        if (peek() != c)
            throw JsonError(line, std::string("expected '") + c + "'");
        ++position;
    }

    bool take_word(std::string_view word)
    {
        if (text.substr(position, word.size()) != word)
            return false;
        position += word.size();
        return true;
    }

    JsonValue parse_value(unsigned depth)
    {
        if (depth > MAX_JSON_DEPTH)
            throw JsonError(line, "nested too deeply");
        JsonValue value;
        char c = peek();
        value.line = line;
        if (c == '{') {
            value.kind = JsonValue::Kind::Object;
            ++position;
            if (peek() == '}') {
                ++position;
                return value;
            }
            while (true) {
                if (peek() != '"')
                    throw JsonError(line, "expected a member name in quotes");
                std::string key = parse_string();
                expect(':');
                value.object.push_back({ key, parse_value(depth + 1) });
                if (peek() == ',') {
                    ++position;
                    continue;
                }
                expect('}');
                return value;
            }
        }
        if (c == '[') {
            value.kind = JsonValue::Kind::Array;
            ++position;
            if (peek() == ']') {
                ++position;
                return value;
            }
            while (true) {
                value.array.push_back(parse_value(depth + 1));
                if (peek() == ',') {
                    ++position;
                    continue;
                }
                expect(']');
                return value;
            }
        }
        if (c == '"') {
            value.kind = JsonValue::Kind::String;
            value.string = parse_string();
            return value;
        }
        if (c == '-' || (c >= '0' && c <= '9')) {
            value.kind = JsonValue::Kind::Number;
            bool negative = c == '-';
            if (negative)
                ++position;
            size_t start = position;
            long long number = 0;
            while (position < text.size() && text[position] >= '0' && text[position] <= '9') {
                number = number * 10 + (text[position] - '0');
                if (number > (1LL << 40))
                    throw JsonError(line, "number too large");
                ++position;
            }
            if (position == start)
                throw JsonError(line, "bad number");
            if (position < text.size() &&
                (text[position] == '.' || text[position] == 'e' || text[position] == 'E'))
                throw JsonError(line, "only integers are allowed");
            value.number = negative ? -number : number;
            return value;
        }
        if (take_word("true")) {
            value.kind = JsonValue::Kind::Boolean;
            value.boolean = true;
            return value;
        }
        if (take_word("false")) {
            value.kind = JsonValue::Kind::Boolean;
            return value;
        }
        if (take_word("null"))
            return value;
        throw JsonError(line, "expected a JSON value");
    }

    std::string parse_string()
    {
        ++position; // opening quote
        std::string result;
        while (true) {
            if (position >= text.size() || text[position] == '\n')
                throw JsonError(line, "unterminated string");
            char c = text[position++];
            if (c == '"')
                return result;
            if (c != '\\') {
                result += c;
                continue;
            }
            if (position >= text.size())
                throw JsonError(line, "unterminated string");
            char escaped = text[position++];
            switch (escaped) {
            case '"': result += '"'; break;
            case '\\': result += '\\'; break;
            case '/': result += '/'; break;
            case 'b': result += '\b'; break;
            case 'f': result += '\f'; break;
            case 'n': result += '\n'; break;
            case 'r': result += '\r'; break;
            case 't': result += '\t'; break;
            case 'u': {
                if (position + 4 > text.size())
                    throw JsonError(line, "bad \\u escape");
                unsigned long code = std::stoul(std::string(text.substr(position, 4)), nullptr, 16);
                position += 4;
                result += encode_utf8(std::u32string(1, static_cast<char32_t>(code)));
                break;
            }
            default: throw JsonError(line, "bad escape in string");
            }
        }
    }
};

const JsonValue &required(const JsonValue &object, const std::string &key, JsonValue::Kind kind)
{
    const JsonValue *value = object.member(key);
    if (value == nullptr)
        throw JsonError(object.line, "missing \"" + key + "\"");
    if (value->kind != kind)
        throw JsonError(value->line, "\"" + key + "\" has the wrong type");
    return *value;
}

long long integer(const JsonValue &object,
                  const std::string &key,
                  long long low,
                  long long high,
                  std::optional<long long> fallback = std::nullopt)
{
    if (fallback && object.member(key) == nullptr)
        return *fallback;
    const JsonValue &value = required(object, key, JsonValue::Kind::Number);
    if (value.number < low || value.number > high)
        throw JsonError(value.line,
                        "\"" + key + "\" must be in [" + std::to_string(low) + ", " +
                          std::to_string(high) + "]");
    return value.number;
}

std::string text_member(const JsonValue &object, const std::string &key, bool optional = false)
{
    if (optional && object.member(key) == nullptr)
        return "";
    return required(object, key, JsonValue::Kind::String).string;
}

const std::vector<JsonValue> &array_member(const JsonValue &object, const std::string &key)
{
    static const std::vector<JsonValue> none;
    if (object.member(key) == nullptr)
        return none;
    return required(object, key, JsonValue::Kind::Array).array;
}

void expect_object(const JsonValue &value)
{
    if (value.kind != JsonValue::Kind::Object)
        throw JsonError(value.line, "expected an object");
}

TargetDescription target_from(const JsonValue &root)
{
    expect_object(root);
    TargetDescription target;
    target.name = text_member(root, "name");
    target.protocol_version =
      static_cast<uint16_t>(integer(root, "protocol_version", 0, WORD_LIMIT, 5));
    target.bytecode_size = static_cast<uint16_t>(integer(root, "bytecode_size", 1, WORD_LIMIT));
    target.variables_size = static_cast<uint16_t>(integer(root, "variables_size", 0, WORD_LIMIT));
    target.stack_size = static_cast<uint16_t>(integer(root, "stack_size", 1, WORD_LIMIT));
    for (const auto &variable : array_member(root, "variables")) {
        expect_object(variable);
        target.named_variables.push_back(
          { text_member(variable, "name"),
            static_cast<uint16_t>(integer(variable, "size", 1, WORD_LIMIT, 1)) });
    }
    for (const auto &event : array_member(root, "local_events")) {
        expect_object(event);
        target.local_events.push_back(
          { text_member(event, "name"), text_member(event, "description", true) });
    }
    for (const auto &native : array_member(root, "natives")) {
        if (native.kind == JsonValue::Kind::String && native.string == "standard") {
            for (auto &function : standard_native_functions())
                target.native_functions.push_back(function);
            continue;
        }
        expect_object(native);
        NativeFunction function;
        function.name = text_member(native, "name");
        function.description = text_member(native, "description", true);
        for (const auto &parameter : array_member(native, "parameters")) {
            expect_object(parameter);
            function.parameters.push_back(
              { text_member(parameter, "name"),
                static_cast<int16_t>(
                  integer(parameter, "size", PARAMETER_SIZE_MIN, PARAMETER_SIZE_MAX)) });
        }
        target.native_functions.push_back(function);
    }
    return target;
}

std::string quoted(const std::string &text)
{
    std::string result = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            result += '\\';
            result += c;
        } else if (c == '\n') {
            result += "\\n";
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char escape[8];
            std::snprintf(escape, sizeof escape, "\\u%04x", c);
            result += escape;
        } else {
            result += c;
        }
    }
    return result + "\"";
}

} // namespace

TargetReadResult read_target_json(std::string_view text)
{
    TargetReadResult result;
    try {
        result.target = target_from(JsonParser(text).parse());
        result.ok = true;
    } catch (const std::exception &error) {
        result.error = error.what();
    }
    return result;
}

std::string write_target_json(const TargetDescription &target)
{
    std::string out = "{\n";
    out += "  \"name\": " + quoted(target.name) + ",\n";
    out += "  \"protocol_version\": " + std::to_string(target.protocol_version) + ",\n";
    out += "  \"bytecode_size\": " + std::to_string(target.bytecode_size) + ",\n";
    out += "  \"variables_size\": " + std::to_string(target.variables_size) + ",\n";
    out += "  \"stack_size\": " + std::to_string(target.stack_size) + ",\n";
    out += "  \"variables\": [";
    for (size_t i = 0; i < target.named_variables.size(); ++i)
        out += std::string(i ? ",\n    " : "\n    ") +
               "{\"name\": " + quoted(target.named_variables[i].name) +
               ", \"size\": " + std::to_string(target.named_variables[i].size) + "}";
    out += "\n  ],\n  \"local_events\": [";
    for (size_t i = 0; i < target.local_events.size(); ++i)
        out += std::string(i ? ",\n    " : "\n    ") +
               "{\"name\": " + quoted(target.local_events[i].name) +
               ", \"description\": " + quoted(target.local_events[i].description) + "}";
    out += "\n  ],\n  \"natives\": [";
    for (size_t i = 0; i < target.native_functions.size(); ++i) {
        const NativeFunction &native = target.native_functions[i];
        out += std::string(i ? ",\n    " : "\n    ") + "{\"name\": " + quoted(native.name) +
               ", \"description\": " + quoted(native.description) + ", \"parameters\": [";
        for (size_t p = 0; p < native.parameters.size(); ++p)
            out += std::string(p ? ", " : "") + "{\"name\": " + quoted(native.parameters[p].name) +
                   ", \"size\": " + std::to_string(native.parameters[p].size) + "}";
        out += "]}";
    }
    out += "\n  ]\n}\n";
    return out;
}

} // namespace aseba
