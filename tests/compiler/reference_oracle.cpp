// Drives Debian's reference compiler library. Its API speaks std::wstring and
// its own description structs; this file converts both ways and nothing else.

#include "reference_oracle.hpp"
#include "reference_containment.hpp"

#include <compiler/compiler.h>
#include <common/utils/utils.h>

#include <locale>
#include <sstream>
#include <stdexcept>

namespace reference
{

namespace
{

// The reference classifies identifier letters with a function-static
// std::locale("en_US.UTF-8"); constructing it throws when the locale is absent.
constexpr const char *required_locale = "en_US.UTF-8";

std::wstring wide(const std::string &text)
{
    return Aseba::UTF8ToWString(text);
}

std::string narrow(const std::wstring &text)
{
    return Aseba::WStringToUTF8(text);
}

Aseba::TargetDescription to_reference(const aseba::TargetDescription &target)
{
    Aseba::TargetDescription description;
    description.name = wide(target.name);
    description.protocolVersion = target.protocol_version;
    description.bytecodeSize = target.bytecode_size;
    description.variablesSize = target.variables_size;
    description.stackSize = target.stack_size;
    for (const aseba::NamedVariable &variable : target.named_variables)
        description.namedVariables.emplace_back(wide(variable.name), variable.size);
    for (const aseba::LocalEvent &event : target.local_events)
        description.localEvents.push_back({ wide(event.name), wide(event.description) });
    for (const aseba::NativeFunction &function : target.native_functions) {
        Aseba::TargetDescription::NativeFunction native;
        native.name = wide(function.name);
        native.description = wide(function.description);
        for (const aseba::NativeParameter &parameter : function.parameters)
            native.parameters.emplace_back(wide(parameter.name), parameter.size);
        description.nativeFunctions.push_back(native);
    }
    return description;
}

Aseba::CommonDefinitions to_reference(const aseba::CommonDefinitions &definitions)
{
    Aseba::CommonDefinitions common;
    for (const aseba::GlobalEvent &event : definitions.events)
        common.events.emplace_back(wide(event.name), event.size);
    for (const aseba::Constant &constant : definitions.constants)
        common.constants.emplace_back(wide(constant.name), constant.value);
    return common;
}

} // namespace

bool reference_locale_available(std::string *why)
{
    // Looking the locale up is slow; its presence does not change while we run.
    static const bool available = [] {
        try {
            const std::locale probe(required_locale);
            return true;
        } catch (const std::runtime_error &) {
            return false;
        }
    }();
    if (!available) {
        if (why)
            *why = std::string("the reference Aseba compiler needs the ") + required_locale +
                   " locale, which this system lacks; run scripts/install-deps.sh (or "
                   "`localedef -i en_US -f UTF-8 en_US.UTF-8`)";
        return false;
    }
    return true;
}

ReferenceResult compile_with_reference(std::string_view source,
                                       const aseba::TargetDescription &target,
                                       const aseba::CommonDefinitions &definitions)
{
    std::string why;
    if (!reference_locale_available(&why))
        throw std::runtime_error(why);

    const Aseba::TargetDescription description = to_reference(target);
    const Aseba::CommonDefinitions common = to_reference(definitions);
    Aseba::Compiler compiler;
    compiler.setTargetDescription(&description);
    compiler.setCommonDefinitions(&common);

    std::wistringstream input(wide(std::string(source)));
    Aseba::BytecodeVector bytecode;
    unsigned allocated = 0;
    Aseba::Error error;

    ReferenceResult result;
    try {
        const ReferenceScope scope;
        result.ok = compiler.compile(input, bytecode, allocated, error);
    } catch (const ReferenceAssertion &failure) {
        result.assertion_failed = true;
        result.error.message = failure.what();
        return result;
    }
    if (!result.ok) {
        result.error.has_position = error.pos.valid;
        if (error.pos.valid) {
            // Upstream stores both 0-based and prints both plus one; a column
            // of "-1" (end of stream at a line start) is printed as 0.
            result.error.line = error.pos.row + 1;
            result.error.column = error.pos.column + 1;
        }
        result.error.message = narrow(error.message);
        return result;
    }
    result.allocated_variables = allocated;
    for (const Aseba::BytecodeElement &element : bytecode) {
        result.bytecode.push_back(element.bytecode);
        result.line_of_word.push_back(element.line);
    }
    for (const auto &[name, position_and_size] : *compiler.getVariablesMap())
        result.variables.push_back(
          { narrow(name), position_and_size.first, position_and_size.second });
    return result;
}

std::string describe(const ReferenceResult &result)
{
    if (result.assertion_failed)
        return "reference assertion failed: " + result.error.message;
    return result.ok ? std::to_string(result.bytecode.size()) + " words" : describe(result.error);
}

std::string describe(const ReferenceError &error)
{
    if (!error.has_position)
        return "Error : " + error.message;
    return "Error at Line: " + std::to_string(error.line) +
           " Col: " + std::to_string(error.column) + " : " + error.message;
}

} // namespace reference
