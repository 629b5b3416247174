// Run-time control of a simulated arena from the tools: one command a line,
// one answer a line, "ok ..." or "error: ...". It is what epuck-emu's
// control port (--control PORT) runs; the commands are in
// docs/arena-format.md ("Run-time control"):
//
//   selector ROBOT POSITION       turn a robot's selector (0..15)
//   rc5 ROBOT COMMAND [ADDRESS]   press a remote key (RC5 command 0..63,
//                                 device 0..31, 0 by default: a TV)
//   status                        time, and each robot's selector and battery
//   help                          the commands
//
// ROBOT is a node id (every robot answering to it) or `all`.

#pragma once

#include <string>

#include "arena_simulation.hpp"

namespace aseba::arena
{

// Carries out the command `line` on `simulation` now, between two steps;
// returns the answer line (without its line end).
std::string run_control_command(ArenaSimulation &simulation, const std::string &line);

} // namespace aseba::arena
