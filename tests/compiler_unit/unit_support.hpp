// What the compiler unit tests share: the reference's dummy node and small
// helpers to compile and compare bytecode.

#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/compiler/compiler.hpp"
#include "tools/compiler/target_presets.hpp"

namespace aseba::unit
{

// Compiles `source` for the dummy node with these global events.
inline CompileResult compile_for_dummy(const std::string &source,
                                       const std::vector<GlobalEvent> &events = {},
                                       const std::vector<Constant> &constants = {})
{
    CommonDefinitions definitions;
    definitions.events = events;
    definitions.constants = constants;
    return compile(source, dummy_target(), definitions);
}

// The code words after the event table.
inline std::vector<uint16_t> code_of(const CompileResult &result)
{
    if (result.bytecode.empty())
        return {};
    return std::vector<uint16_t>(result.bytecode.begin() + result.bytecode[0],
                                 result.bytecode.end());
}

} // namespace aseba::unit
