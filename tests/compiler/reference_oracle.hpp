// The reference Aseba compiler (Debian's libasebacompiler, upstream 1.6.99)
// behind our own compiler's types, so that tests can compare the two. Only
// tests use it: it is the oracle our compiler must match word for word.

#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tools/compiler/target.hpp"

namespace reference
{

struct ReferenceError {
    bool has_position = false;
    unsigned line = 0;   // 1-based, as upstream prints it
    unsigned column = 0; // 1-based; 0 for an end of stream at a line start
    std::string message;
};

struct ReferenceResult {
    bool ok = false;
    // The reference failed one of its own assertions (an upstream bug, e.g.
    // on `a[[b]]`): neither ok nor a compile error; the text is in error.message.
    bool assertion_failed = false;
    std::vector<uint16_t> bytecode;
    std::vector<unsigned> line_of_word; // as upstream records it (0-based lines)
    unsigned allocated_variables = 0;
    // Every variable the reference knows (named and user): name, address, size.
    struct Variable {
        std::string name;
        unsigned address = 0;
        unsigned size = 0;
    };
    std::vector<Variable> variables;
    ReferenceError error; // when !ok
};

// Whether the locale the reference compiler needs (en_US.UTF-8) exists; when
// it does not, `why` says how to get it.
bool reference_locale_available(std::string *why);

// Compiles UTF-8 `source` with the reference compiler for `target` and
// `definitions`. Throws std::runtime_error (with a clear message) only when
// the reference cannot run at all, e.g. without the en_US.UTF-8 locale.
ReferenceResult compile_with_reference(std::string_view source,
                                       const aseba::TargetDescription &target,
                                       const aseba::CommonDefinitions &definitions);

// Renders an error as upstream does: "Error at Line: L Col: C : message".
std::string describe(const ReferenceError &error);

// The outcome in one line: the size of the bytecode, or the error.
std::string describe(const ReferenceResult &result);

} // namespace reference
