// Random valid Aseba programs, as assembler listings: expressions with every
// operator (shifts by any count, divisions by values that may be zero),
// indirect loads and stores with in- and out-of-range indices, if / when
// branches, bounded loops, subroutine calls, emits and calls of the harness'
// natives, in several event handlers.
//
// "Valid" means what the reference VM needs to stay defined (bytecode.md §8.5
// and §11): the stack never overflows, every LOAD/STORE/EMIT address is
// inside the variables, every jump inside the code, loops end. Run-time
// errors that both VMs report (array access, division by zero, the failing
// native) are allowed. Early code is padded so that the upstream
// reset-when-flags walk (§5.1) sees every branch.

#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace vm_tests
{

// The memory the generated programs assume.
struct RandomProgramLayout {
    static constexpr uint16_t VARIABLES = 128;
    static constexpr uint16_t ARGS = 8; // args at 2 .. 9
    static constexpr uint16_t STACK = 32;
    static constexpr uint16_t BYTECODE = 1536;
};

// The user events the programs handle, besides init; kUnhandledEvent is not.
inline constexpr uint16_t random_program_events[] = { 0, 1, 0xFFFE };
inline constexpr uint16_t random_program_unhandled_event = 2;

struct RandomProgramOptions {
    unsigned statements_per_block = 6;
    unsigned subroutines = 3;
    bool natives = true;
    bool failing_native = true;
};

// A listing for tests/support/assembler.hpp.
std::string random_program(std::mt19937 &random, const RandomProgramOptions &options = {});

} // namespace vm_tests
