// `asebac run`: executes compiled bytecode on the host VM and reports the
// variables, emitted events and run-time errors as JSON.

#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/compiler/compiler.hpp"

namespace aseba
{

struct EventToSend {
    std::string name;
    std::vector<int16_t> arguments;
};

// What a run left: the whole variable memory, what the program emitted
// (JSON objects), run-time errors (JSON objects) and the events still running
// when their budget ran out.
struct RunOutcome {
    std::vector<int16_t> memory;
    std::vector<std::string> emitted;
    std::vector<std::string> errors;
    std::vector<std::string> unfinished;
};

// Loads `compiled` into a VM for `target`, runs init and then `events` in
// order, each for at most `step_budget` instructions. Fails (returns false,
// `error` set) if the target has a native the host has no implementation
// for, or an event is unknown.
bool execute_program(const CompileResult &compiled,
                     const TargetDescription &target,
                     const CommonDefinitions &definitions,
                     const std::vector<EventToSend> &events,
                     unsigned long step_budget,
                     RunOutcome &outcome,
                     std::string &error);

// execute_program, with its outcome as the JSON report of `asebac run`.
bool run_program(const CompileResult &compiled,
                 const TargetDescription &target,
                 const CommonDefinitions &definitions,
                 const std::vector<EventToSend> &events,
                 unsigned long step_budget,
                 std::string &report,
                 std::string &error);

} // namespace aseba
