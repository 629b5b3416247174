// Variable names to addresses, and the `name[i:j]` syntax.

#include "variables.hpp"

#include <cctype>
#include <cstdlib>

namespace aseba::client
{

namespace
{

unsigned parse_index(const std::string &text, const std::string &reference)
{
    char *end = nullptr;
    unsigned long value = std::strtoul(text.c_str(), &end, 10);
    if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0])) || *end != '\0' ||
        value > UINT16_MAX)
        throw VariableError("'" + reference + "': index '" + text +
                            "' is not a whole number from 0 to 65535");
    return unsigned(value);
}

} // namespace

std::vector<VariableLocation> variable_map(const TargetDescription &description,
                                           const CompiledProgram *program)
{
    std::vector<VariableLocation> map;
    uint16_t address = 0;
    for (const NamedVariable &variable : description.named_variables) {
        map.push_back({ variable.name, address, variable.size, true });
        address = uint16_t(address + variable.size);
    }
    if (program != nullptr)
        for (const VariableInfo &variable : program->result.variables)
            if (variable.address >= address) // the compiler lists named ones too
                map.push_back({ variable.name, variable.address, variable.size, false });
    return map;
}

VariableReference parse_variable_reference(const std::string &text)
{
    VariableReference reference;
    size_t bracket = text.find('[');
    reference.name = text.substr(0, bracket);
    if (reference.name.empty())
        throw VariableError("'" + text + "': no variable name");
    if (bracket == std::string::npos)
        return reference;
    if (text.back() != ']')
        throw VariableError("'" + text + "': expected NAME, NAME[i] or NAME[i:j]");
    std::string inside = text.substr(bracket + 1, text.size() - bracket - 2);
    size_t colon = inside.find(':');
    reference.first = parse_index(inside.substr(0, colon), text);
    reference.last =
      colon == std::string::npos ? reference.first : parse_index(inside.substr(colon + 1), text);
    if (*reference.last < *reference.first)
        throw VariableError("'" + text + "': the range ends before it starts");
    return reference;
}

VariableSlice resolve_variable(const VariableReference &reference,
                               const std::vector<VariableLocation> &map)
{
    for (const VariableLocation &variable : map) {
        if (variable.name != reference.name)
            continue;
        VariableSlice slice;
        slice.text = reference.name;
        slice.address = variable.address;
        slice.length = variable.size;
        if (reference.first) {
            if (*reference.last >= variable.size)
                throw VariableError("'" + reference.name + "' has " +
                                    std::to_string(variable.size) + " element" +
                                    (variable.size == 1 ? "" : "s") + ", index " +
                                    std::to_string(*reference.last) + " is out of range");
            slice.address = uint16_t(variable.address + *reference.first);
            slice.length = uint16_t(*reference.last - *reference.first + 1);
            slice.text += "[" + std::to_string(*reference.first);
            if (*reference.last != *reference.first)
                slice.text += ":" + std::to_string(*reference.last);
            slice.text += "]";
        }
        return slice;
    }
    throw VariableError("no variable '" + reference.name + "' on this node" +
                        " (user variables are known only with the program that declares them)");
}

} // namespace aseba::client
