// The Aseba compiler: source text to protocol-5 bytecode for one target,
// bit-identical to the reference compiler for every program it accepts.

#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "target.hpp"

namespace aseba
{

// 1-based line and column (in characters) of the source text.
struct SourcePosition {
    unsigned line = 0;
    unsigned column = 0;
};

struct CompileError {
    bool has_position = false; // a few errors (stack overflow) have none
    SourcePosition position;
    std::string message;
};

// A user variable as allocated by the compiler (named variables come first).
struct VariableInfo {
    std::string name;
    uint16_t address = 0;
    uint16_t size = 0;
};

// A local variable or parameter (docs/language.md), at its fixed address.
struct LocalVariableInfo {
    std::string name;
    std::string owner; // "onevent NAME", "sub NAME" or "the code before the first onevent"
    uint16_t address = 0;
    uint16_t size = 0;
};

struct CompileResult {
    bool ok = false;
    std::vector<uint16_t> bytecode;        // event table then code
    std::vector<unsigned> line_of_word;    // source line of each bytecode word
    std::vector<VariableInfo> variables;   // user variables in address order
    std::vector<LocalVariableInfo> locals; // in source order
    uint16_t locals_words = 0;             // the shared area of the locals, after the globals
    uint16_t allocated_variables = 0;      // named, user and local words, temporaries excluded
    CompileError error;                    // when !ok
};

// The longest source text compile() takes, in bytes.
inline constexpr size_t MAX_SOURCE_BYTES = 1024 * 1024;

// Compiles `source` (UTF-8) for `target` with the project's `definitions`.
// Never throws on bad input: errors come back in the result.
CompileResult compile(std::string_view source,
                      const TargetDescription &target,
                      const CommonDefinitions &definitions);

} // namespace aseba
