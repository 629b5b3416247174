// The dangerous-area experiment of the 2007 Aseba paper (its Fig. 5) in the
// simulated arena: robots running the paper's controller, with the robots'
// radio and the experimenter's shocks each switched on or off, and the
// simulated time each robot spends on a dangerous colour.
//
// A dangerous area is one that shocks robots in the arena as given; it stays
// dangerous (it is measured) when the shocks are switched off.

#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/emulator/arena_file.hpp"

namespace aseba::experiment
{

// One of the paper's four conditions.
struct Condition {
    bool communication = true; // robots hear each other's `bad` events
    bool shocks = true;        // dangerous areas knock the robots on them
};

// The four conditions in the order the report shows them: both on, shocks
// only, communication only, neither.
std::vector<Condition> all_conditions();

// A short name such as "shocks+communication" or "neither".
std::string condition_name(const Condition &condition);

// The arena as the condition wants it: `arena` with no shock at all when the
// shocks are off, else unchanged.
arena::Arena arena_for(const arena::Arena &arena, const Condition &condition);

// Which areas of `arena` are dangerous: those with a shock period.
std::vector<bool> dangerous_areas(const arena::Arena &arena);

// The area whose colour the floor shows at (x, y) (later areas paint over
// earlier ones), or -1 for the bare floor.
int area_at(const arena::Arena &arena, double x, double y);

// What one robot did in one run.
struct RobotTimes {
    uint16_t node_id = 0;
    double seconds_on_dangerous = 0;     // centre on a dangerous area
    std::vector<double> seconds_on_area; // centre on each area, arena order
    unsigned events_emitted = 0;         // user events (the annex's alarms) sent
};

// One run: the condition, the seed, its duration and every robot's times.
struct RunResult {
    Condition condition;
    uint32_t seed = 0;
    double seconds = 0; // whole world steps
    std::vector<RobotTimes> robots;
};

// Runs `arena` under `condition` for `seconds` simulated seconds (whole
// world steps) with `bytecode` (may be empty) on every robot, at full speed
// and with no tool on the network, and measures after every world step
// where each robot's centre is; counts the user events each robot emits
// (whether or not the radio relays them). The same inputs give the same
// result.
RunResult run_condition(const arena::Arena &arena,
                        const Condition &condition,
                        uint32_t seed,
                        double seconds,
                        const std::vector<uint16_t> &bytecode);

// Compiles the e-puck program of the project or script at `path` (the node
// named e-puck when the project has one); throws std::runtime_error with the
// compiler's message when it does not compile.
std::vector<uint16_t> compile_for_epuck(const std::string &path);

} // namespace aseba::experiment
