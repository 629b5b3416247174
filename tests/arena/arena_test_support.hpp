// What the arena tests share: a program compiled for the e-puck, and a
// robot's variables as its firmware holds them.

#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_presets.hpp"
#include "tools/emulator/arena_simulation.hpp"

namespace arena_test
{

// The bytecode of the program (.aesl or script) at `path`; a compile error
// fails the test.
inline std::vector<uint16_t> compile(const std::string &path)
{
    aseba::ProgramFile program = aseba::read_program_file(path, "");
    std::string error;
    aseba::CompileResult result =
      aseba::compile_program_file(program, aseba::epuck_target(), error);
    EXPECT_TRUE(result.ok) << error;
    return result.bytecode;
}

inline epuck_named_variables &variables(aseba::arena::ArenaSimulation &simulation, size_t robot = 0)
{
    return simulation.firmware(robot).variables.named;
}

} // namespace arena_test
