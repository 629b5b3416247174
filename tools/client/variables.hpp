// Variables by name: where each variable of a node lives (the named
// variables of its description, then the user variables of the program this
// client loaded), and references like `camR`, `camR[3]` or `camR[0:9]`
// (inclusive bounds, as in the Aseba language).

#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "program.hpp"
#include "tools/compiler/target.hpp"

namespace aseba::client
{

// An unknown variable, a bad reference or an index out of range.
class VariableError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

struct VariableLocation {
    std::string name;
    uint16_t address = 0;
    uint16_t size = 0;
    bool named = true; // false for a user variable of the loaded program
};

// The node's variables in address order: named ones from `description`,
// then the user variables of `program` if there is one.
std::vector<VariableLocation> variable_map(const TargetDescription &description,
                                           const CompiledProgram *program);

// A parsed reference: a name and an optional index or inclusive range.
struct VariableReference {
    std::string name;
    std::optional<unsigned> first;
    std::optional<unsigned> last; // equal to first for a single index
};

// Parses `name`, `name[i]` or `name[i:j]`; throws VariableError.
VariableReference parse_variable_reference(const std::string &text);

// The words a reference designates.
struct VariableSlice {
    std::string text;     // as people read it, e.g. "camR[0:9]"
    uint16_t address = 0; // of the first word
    uint16_t length = 0;  // words
};

// Resolves `reference` in `map`; throws VariableError naming the problem.
VariableSlice resolve_variable(const VariableReference &reference,
                               const std::vector<VariableLocation> &map);

} // namespace aseba::client
