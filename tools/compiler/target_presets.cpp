// The built-in targets. The e-puck preset is read from the same lists the
// firmware compiles (firmware/epuck_description.h, the natives' C table), so
// that the compiler and the robot cannot disagree.

#include "target_presets.hpp"

extern "C" {
#include "firmware/epuck_description.h"
#include "firmware/epuck_natives.h"
#include "nat_standard.h"
}

namespace aseba
{

namespace
{

// The reference's dummy node (bytecode.md §1): sizes and named variables.
constexpr uint16_t DUMMY_BYTECODE_WORDS = 512;
constexpr uint16_t DUMMY_STACK_WORDS = 64;
constexpr uint16_t DUMMY_VARIABLE_WORDS = 1060;
constexpr uint16_t DUMMY_ARGS_WORDS = 32;
constexpr uint16_t PROTOCOL_VERSION = 5;

} // namespace

// A C native table as the compiler sees natives.
static std::vector<NativeFunction> native_functions(const vm_native_table &table)
{
    std::vector<NativeFunction> natives;
    for (uint16_t i = 0; i < table.count; ++i) {
        const vm_native &native = *table.natives[i];
        NativeFunction function;
        function.name = native.name;
        function.description = native.description;
        for (uint8_t p = 0; p < native.parameter_count; ++p)
            function.parameters.push_back({ native.parameters[p].name, native.parameters[p].size });
        natives.push_back(function);
    }
    return natives;
}

std::vector<NativeFunction> standard_native_functions()
{
    return native_functions(nat_standard_table);
}

TargetDescription epuck_target()
{
    TargetDescription target;
    target.name = EPUCK_NAME;
    target.protocol_version = PROTOCOL_VERSION;
    target.bytecode_size = EPUCK_BYTECODE_WORDS;
    target.stack_size = EPUCK_STACK_WORDS;
    unsigned named_words = 0;
#define EPUCK_ADD_VARIABLE(identifier, name, size)                                                 \
    target.named_variables.push_back({ name, size });                                              \
    named_words += size;
    EPUCK_VARIABLE_LIST(EPUCK_ADD_VARIABLE)
#undef EPUCK_ADD_VARIABLE
#define EPUCK_ADD_EVENT(identifier, name, description)                                             \
    target.local_events.push_back({ name, description });
    EPUCK_LOCAL_EVENT_LIST(EPUCK_ADD_EVENT)
#undef EPUCK_ADD_EVENT
    target.variables_size = static_cast<uint16_t>(named_words + EPUCK_FREE_WORDS);
    target.native_functions = native_functions(epuck_native_table);
    return target;
}

TargetDescription dummy_target()
{
    TargetDescription target;
    target.name = "dummynode-0";
    target.protocol_version = PROTOCOL_VERSION;
    target.bytecode_size = DUMMY_BYTECODE_WORDS;
    target.stack_size = DUMMY_STACK_WORDS;
    target.variables_size = DUMMY_VARIABLE_WORDS;
    target.named_variables = { { "id", 1 },
                               { "source", 1 },
                               { "args", DUMMY_ARGS_WORDS },
                               { "_productId", 1 },
                               { "timer.period", 1 } };
    target.local_events = { { "timer", "periodic timer" } };
    target.native_functions = standard_native_functions();
    return target;
}

std::optional<TargetDescription> target_preset(const std::string &name)
{
    if (name == "epuck")
        return epuck_target();
    if (name == "dummy")
        return dummy_target();
    return std::nullopt;
}

} // namespace aseba
