// What the phases of one compilation share: the target, the project's
// definitions, the symbols declared so far and the temporaries in use.

#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "compiler.hpp"
#include "syntax_tree.hpp"

namespace aseba
{

struct Compilation {
    const TargetDescription &target;
    const CommonDefinitions &definitions;

    std::vector<VariableInfo> variables; // named variables, then user variables
    size_t named_variable_count = 0;
    unsigned next_free_address = 0;           // first word after the user variables
    std::map<std::string, int64_t> constants; // global and source constants
    unsigned temporaries_used = 0;            // words taken from the end of memory

    std::vector<std::string> subroutines; // in definition order
    std::vector<unsigned> implemented_events;

    Compilation(const TargetDescription &target_description,
                const CommonDefinitions &common_definitions);

    const VariableInfo *find_variable(const std::string &name) const;
    std::optional<int64_t> find_constant(const std::string &name) const;
    std::optional<unsigned> find_global_event(const std::string &name) const;
    std::optional<unsigned> find_local_event(const std::string &name) const;
    std::optional<unsigned> find_native(const std::string &name) const;
    std::optional<unsigned> find_subroutine(const std::string &name) const;

    // The address of `size` fresh words at the end of memory (language.md §7).
    unsigned allocate_temporary(unsigned size, SourcePosition where);
};

// The closest of `candidates` to `name` (edit distance < 3; ties go to the
// alphabetically first), or "" when none is close.
std::string closest_name(const std::string &name, const std::vector<std::string> &candidates);

// `message` completed with ", do you mean X?" when a close candidate exists.
std::string with_suggestion(const std::string &message,
                            const std::string &name,
                            const std::vector<std::string> &candidates);

// Parses `tokens` into the program tree (a Block), declaring variables and
// constants and allocating parse-time temporaries in `compilation`.
NodePointer parse_program(const std::vector<struct Token> &tokens, Compilation &compilation);

// Throws the bounds error of language.md §6 if a constant index or slice of
// a Memory node leaves its variable (the end is checked first).
void check_constant_index(const Node &memory);

// Checks vector sizes (language.md §6) of the whole program.
void check_sizes(Node &program);

// The number of words `expression` denotes; throws the size error on mismatch.
unsigned vector_size(const Node &expression);

// Rewrites op=, ++ and -- and expands vector statements into scalar ones.
void expand_program(Node &program, Compilation &compilation);

// Checks types (language.md §5) of the expanded program and that called
// subroutines exist.
void check_types(Node &program, const Compilation &compilation);

// Applies the optimisations of language.md §9; returns the simplified node,
// or null when a statement disappears.
NodePointer optimize(NodePointer node);

// Evaluates a constant expression without variables, if it is one. With
// `report_errors`, a division by zero in it is an error, else just no value.
std::optional<int64_t> evaluate_constant(const Node &expression, bool report_errors = false);

} // namespace aseba
