// The built-in targets. The e-puck preset is read from the same lists the
// firmware compiles (robots/epuck/epuck_description.h, the natives' C table,
// the memory sizes of the host target's configuration, which vm.h includes), so
// that the compiler and the robot cannot disagree.

#include "target_presets.hpp"

extern "C" {
#include "robots/epuck/epuck_description.h"
#include "robots/epuck/epuck_natives.h"
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

// A text of a packed native description (vm.h), expanded.
static std::string native_text(const char *words, const char *text)
{
    vm_native_text reader{ words, text, nullptr };
    std::string expanded;
    while (uint8_t byte = vm_native_text_next(&reader))
        expanded += char(byte);
    return expanded;
}

NativeFunction native_function(const vm_native_table &table, uint16_t index)
{
    const char *description = vm_native_name(vm_native_at(&table, index));
    NativeFunction function;
    function.name = native_text(table.words, description);
    const char *part = vm_native_text_end(description);
    if (uint8_t(*part) == VM_NATIVE_DOCUMENTATION_MARK) {
        function.description = native_text(table.words, part + 1);
        part = vm_native_text_end(part + 1);
    }
    for (; *part != '\0'; part = vm_native_text_end(part + 1))
        function.parameters.push_back(
          { native_text(table.words, part + 1), int16_t(uint8_t(*part) - VM_NATIVE_SIZE_BIAS) });
    return function;
}

std::vector<NativeFunction> native_functions(const vm_native_table &table)
{
    std::vector<NativeFunction> natives;
    for (uint16_t i = 0; i < vm_native_count(&table); ++i)
        natives.push_back(native_function(table, i));
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
    target.bytecode_size = FIRMWARE_BYTECODE_WORDS;
    target.stack_size = FIRMWARE_STACK_WORDS;
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
    target.variables_size = static_cast<uint16_t>(named_words + FIRMWARE_FREE_VARIABLE_WORDS);
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
