// What a compilation needs to know beyond the source text: the node it
// compiles for (as the node describes itself in DESCRIPTION messages) and the
// project's global events and constants (language.md §1, aesl.md).

#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace aseba
{

struct NamedVariable {
    std::string name;
    uint16_t size = 1;
};

struct LocalEvent {
    std::string name;
    std::string description;
};

struct NativeParameter {
    std::string name;
    int16_t size = 1; // > 0 fixed, < 0 template id, 0 any size
};

struct NativeFunction {
    std::string name;
    std::string description;
    std::vector<NativeParameter> parameters;
};

// A node's DESCRIPTION: sizes in words, and its named variables, local events
// and native functions, each in the node's order.
struct TargetDescription {
    std::string name;
    uint16_t protocol_version = 5;
    uint16_t bytecode_size = 0;
    uint16_t variables_size = 0;
    uint16_t stack_size = 0;
    std::vector<NamedVariable> named_variables;
    std::vector<LocalEvent> local_events;
    std::vector<NativeFunction> native_functions;
};

struct GlobalEvent {
    std::string name;
    uint16_t size = 0; // words of arguments
};

// The protocol's longest event: 258 words of arguments (protocol.md §2).
constexpr uint16_t MAX_EVENT_WORDS = 258;

// A global event as command lines declare it, NAME or NAME:SIZE (size 0 when
// omitted); throws std::invalid_argument saying what is wrong.
GlobalEvent parse_event_declaration(const std::string &text);

struct Constant {
    std::string name;
    int16_t value = 0;
};

// The project-wide definitions shared by all nodes, in declaration order.
struct CommonDefinitions {
    std::vector<GlobalEvent> events;
    std::vector<Constant> constants;
};

} // namespace aseba
