// What the phases of one compilation share: the target, the project's
// definitions, the symbols declared so far and the temporaries in use.

#pragma once

#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "compiler.hpp"
#include "syntax_tree.hpp"

namespace aseba
{

// The code of one section of the program (the code before the first
// `onevent`, a handler or a subroutine) and the locals it holds at once.
struct Frame {
    std::string title;         // "onevent ir_sensors", "sub clamp", "the init code"
    SourcePosition start;      // its `onevent`/`sub` name (line 1 for the init code)
    unsigned size = 0;         // most words of locals, parameters and scratch in use at once
    SourcePosition largest_at; // where that most was reached
    unsigned base = 0;         // its place in the locals area, once laid out

    // A call of a subroutine from this frame, with the words of this frame
    // in use during the call (the callee's frame goes after them).
    struct CallSite {
        std::string callee;
        unsigned words_in_use = 0;
        SourcePosition position;
    };
    std::vector<CallSite> calls;
};

// What a call needs to know of a subroutine (docs/language.md).
struct Subroutine {
    std::string name;
    SourcePosition position;
    unsigned frame = 0;              // index in Compilation::frames
    bool has_parameter_list = false; // written `sub name(...)`
    struct Parameter {
        std::string name;
        unsigned size = 1;
        unsigned offset = 0; // in the frame
    };
    std::vector<Parameter> parameters;
    std::vector<SourcePosition> valued_returns; // `return e`
    std::vector<SourcePosition> bare_returns;   // `return` in a subroutine with a list
    bool returns_value() const
    {
        return !valued_returns.empty();
    }
};

// A local variable or parameter, for listings.
struct LocalVariable {
    std::string name;
    unsigned frame = 0;
    unsigned offset = 0; // in the frame
    unsigned size = 1;
};

struct Compilation {
    const TargetDescription &target;
    const CommonDefinitions &definitions;

    std::vector<VariableInfo> variables; // named variables, then user variables
    // Name -> index in `variables` (the first of that name): every name in
    // the program is looked up, and scanning the list took a good share of
    // the parsing. Filled by add_variable.
    std::unordered_map<std::string, size_t> variable_index;
    size_t named_variable_count = 0;
    unsigned next_free_address = 0;           // first word after the user variables
    std::map<std::string, int64_t> constants; // global and source constants
    unsigned temporaries_used = 0;            // words taken from the end of memory
    unsigned most_temporaries_used = 0;       // the most at once, for the final memory check

    std::vector<std::string> subroutines; // in definition order
    std::map<std::string, unsigned> subroutine_index;
    std::vector<Subroutine> signatures; // the same subroutines, with their parameters
    std::vector<unsigned> implemented_events;

    std::vector<Frame> frames; // in source order: the init code, then each onevent and sub
    std::vector<LocalVariable> locals;
    unsigned locals_start = 0; // first word of the locals area: after every global
    unsigned locals_size = 0;

    // The absolute address of `offset` in `frame`, once the area is laid out.
    unsigned local_address(unsigned frame, unsigned offset) const
    {
        return locals_start + frames[frame].base + offset;
    }

    Compilation(const TargetDescription &target_description,
                const CommonDefinitions &common_definitions);

    void add_variable(const VariableInfo &variable);
    const VariableInfo *find_variable(const std::string &name) const;
    std::optional<int64_t> find_constant(const std::string &name) const;
    std::optional<unsigned> find_global_event(const std::string &name) const;
    std::optional<unsigned> find_local_event(const std::string &name) const;
    std::optional<unsigned> find_native(const std::string &name) const;
    std::optional<unsigned> find_subroutine(const std::string &name) const;
    // The subroutine `name`; else throws `unknown` at `where`, with a suggestion.
    const Subroutine &called_subroutine(const std::string &name,
                                        SourcePosition where,
                                        const std::string &unknown) const;

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

// Checks the calls of subroutines with parameters and their returns, lays
// out the locals area (docs/language.md) and makes every address absolute.
void allocate_locals(Node &program, Compilation &compilation);

// Throws if the globals, the locals area and the scratch words at the end of
// memory do not fit in the target's variables together.
void check_memory(const Compilation &compilation);

// Whether `node` calls a subroutine in an expression (or is such a call).
bool contains_call(const Node &node);

// Whether the variable called `name` appears in `expression`.
bool mentions(const Node &expression, const std::string &name);

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
