// Code generation (language.md §8), the stack-depth check (§11.3) and the
// linker (§10).

#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "compilation.hpp"

namespace aseba
{

// The most words an instruction takes (vm_opcodes.h: EMIT).
constexpr unsigned MAX_INSTRUCTION_WORDS = 3;

// The words are kept in the instruction rather than in a vector of their
// own: a program has thousands of instructions, and one allocation each
// made code generation slow.
struct Instruction {
    std::array<uint16_t, MAX_INSTRUCTION_WORDS> words{};
    unsigned word_count = 0; // the first `word_count` of `words` are used
    unsigned line = 0;
    int subroutine = -1; // SUB_CALL: index of the called subroutine, patched by the linker
};

// The instruction of `words` (at most MAX_INSTRUCTION_WORDS) from `line`.
inline Instruction make_instruction(std::initializer_list<uint16_t> words,
                                    unsigned line,
                                    int subroutine = -1)
{
    Instruction instruction;
    for (uint16_t word : words)
        instruction.words[instruction.word_count++] = word;
    instruction.line = line;
    instruction.subroutine = subroutine;
    return instruction;
}

using Code = std::vector<Instruction>;

// A call of a subroutine, with the stack words in use under it.
struct StackCall {
    unsigned subroutine = 0; // index in definition order
    unsigned words_below = 0;
    SourcePosition position;
};

// The code of one event handler or subroutine before linking.
struct Section {
    bool is_subroutine = false;
    unsigned event_id = 0;   // events
    unsigned subroutine = 0; // subroutines: index in definition order
    SourcePosition start;    // its `onevent` or `sub` name
    Code code;
    unsigned stack_depth = 0;  // deepest statement, calls aside
    SourcePosition deepest_at; // that statement
    std::vector<StackCall> calls;
    unsigned last_line = 0;
};

// The sections of the optimised `program`: init first, then one per
// `onevent`/`sub` marker in source order.
std::vector<Section> generate_code(const Node &program, const Compilation &compilation);

// Throws if subroutines call each other in a cycle (naming it), or if a
// handler or subroutine may overflow the target's stack.
void check_stack(const std::vector<Section> &sections, const Compilation &compilation);

// Lays out the event table, handlers and subroutines (§10) into `result`.
void link(std::vector<Section> sections, const Compilation &compilation, CompileResult &result);

} // namespace aseba
