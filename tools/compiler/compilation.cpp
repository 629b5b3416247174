// Symbol tables of one compilation and the name suggestions of language.md §7.

#include "compilation.hpp"

#include <algorithm>

#include "diagnostics.hpp"
#include "lexer.hpp"

namespace aseba
{

namespace
{

constexpr size_t SUGGESTION_DISTANCE_LIMIT = 3; // suggest names closer than this

size_t edit_distance(const std::u32string &a, const std::u32string &b)
{
    std::vector<size_t> previous(b.size() + 1), row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j)
        previous[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
            row[j] = std::min({ previous[j] + 1, row[j - 1] + 1, substitution });
        }
        std::swap(previous, row);
    }
    return previous[b.size()];
}

} // namespace

Compilation::Compilation(const TargetDescription &target_description,
                         const CommonDefinitions &common_definitions)
  : target(target_description)
  , definitions(common_definitions)
{
    unsigned address = 0;
    for (const auto &named : target.named_variables) {
        add_variable({ named.name, static_cast<uint16_t>(address), named.size });
        address += named.size;
    }
    named_variable_count = variables.size();
    frames.push_back({ "the code before the first onevent", { 1, 1 }, 0, {}, 0, {} });
    next_free_address = address;
    if (address > target.variables_size)
        throw CompileFailure("Broken target description: not enough room for internal variables");
    for (const auto &constant : definitions.constants)
        constants.emplace(constant.name, constant.value);
}

void Compilation::add_variable(const VariableInfo &variable)
{
    variable_index.emplace(variable.name, variables.size()); // keeps an earlier one
    variables.push_back(variable);
}

const VariableInfo *Compilation::find_variable(const std::string &name) const
{
    auto found = variable_index.find(name);
    if (found == variable_index.end())
        return nullptr;
    return &variables[found->second];
}

std::optional<int64_t> Compilation::find_constant(const std::string &name) const
{
    auto found = constants.find(name);
    if (found == constants.end())
        return std::nullopt;
    return found->second;
}

std::optional<unsigned> Compilation::find_global_event(const std::string &name) const
{
    for (size_t i = 0; i < definitions.events.size(); ++i)
        if (definitions.events[i].name == name)
            return static_cast<unsigned>(i);
    return std::nullopt;
}

std::optional<unsigned> Compilation::find_local_event(const std::string &name) const
{
    for (size_t i = 0; i < target.local_events.size(); ++i)
        if (target.local_events[i].name == name)
            return static_cast<unsigned>(0xFFFE - i);
    return std::nullopt;
}

std::optional<unsigned> Compilation::find_native(const std::string &name) const
{
    for (size_t i = 0; i < target.native_functions.size(); ++i)
        if (target.native_functions[i].name == name)
            return static_cast<unsigned>(i);
    return std::nullopt;
}

std::optional<unsigned> Compilation::find_subroutine(const std::string &name) const
{
    auto found = subroutine_index.find(name);
    if (found == subroutine_index.end())
        return std::nullopt;
    return found->second;
}

const Subroutine &Compilation::called_subroutine(const std::string &name,
                                                 SourcePosition where,
                                                 const std::string &unknown) const
{
    std::optional<unsigned> index = find_subroutine(name);
    if (!index)
        fail(where, with_suggestion(unknown, name, subroutines));
    return signatures[*index];
}

unsigned Compilation::allocate_temporary(unsigned size, SourcePosition where)
{
    if (next_free_address + temporaries_used + size > target.variables_size)
        fail(where, "Not enough free space to allocate this tempory variable");
    temporaries_used += size;
    most_temporaries_used = std::max(most_temporaries_used, temporaries_used);
    return target.variables_size - temporaries_used;
}

std::string closest_name(const std::string &name, const std::vector<std::string> &candidates)
{
    std::u32string wanted = decode_utf8(name);
    std::string best;
    size_t best_distance = SUGGESTION_DISTANCE_LIMIT;
    for (const auto &candidate : candidates) {
        size_t distance = edit_distance(wanted, decode_utf8(candidate));
        if (distance < best_distance ||
            (distance == best_distance && !best.empty() && distance < SUGGESTION_DISTANCE_LIMIT &&
             candidate < best)) {
            best = candidate;
            best_distance = distance;
        }
    }
    return best;
}

std::string with_suggestion(const std::string &message,
                            const std::string &name,
                            const std::vector<std::string> &candidates)
{
    std::string suggestion = closest_name(name, candidates);
    if (suggestion.empty())
        return message;
    return message + ", do you mean " + suggestion + "?";
}

} // namespace aseba
