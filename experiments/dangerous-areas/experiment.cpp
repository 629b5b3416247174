// The dangerous-area experiment's runs and measurement (see experiment.hpp).

#include "experiment.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

#include "tools/emulator/arena_simulation.hpp"
#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "robots/epuck/epuck_description.h"
#include "vm/node_protocol.h"
}

namespace aseba::experiment
{

std::vector<Condition> all_conditions()
{
    return {
        { .communication = true, .shocks = true },
        { .communication = false, .shocks = true },
        { .communication = true, .shocks = false },
        { .communication = false, .shocks = false },
    };
}

std::string condition_name(const Condition &condition)
{
    if (condition.shocks && condition.communication)
        return "shocks+communication";
    if (condition.shocks)
        return "shocks only";
    if (condition.communication)
        return "communication only";
    return "neither";
}

arena::Arena arena_for(const arena::Arena &arena, const Condition &condition)
{
    arena::Arena result = arena;
    if (!condition.shocks)
        for (arena::GroundArea &area : result.areas)
            area.shock_period = 0;
    return result;
}

std::vector<bool> dangerous_areas(const arena::Arena &arena)
{
    std::vector<bool> dangerous;
    for (const arena::GroundArea &area : arena.areas)
        dangerous.push_back(area.shock_period > 0);
    return dangerous;
}

int area_at(const arena::Arena &arena, double x, double y)
{
    for (size_t i = arena.areas.size(); i-- > 0;)
        if (arena.areas[i].contains(x, y))
            return int(i);
    return -1;
}

RunResult run_condition(const arena::Arena &arena,
                        const Condition &condition,
                        uint32_t seed,
                        double seconds,
                        const std::vector<uint16_t> &bytecode)
{
    const std::vector<bool> dangerous = dangerous_areas(arena);
    arena::ArenaSimulation simulation(arena_for(arena, condition), seed, bytecode);
    simulation.network().relay_robot_events(condition.communication);

    // A frame is length, source, type, payload (protocol.md §2); types
    // below NODE_FIRST_SYSTEM_TYPE are user events.
    std::map<uint16_t, unsigned> events_by_node;
    simulation.network().observe([&events_by_node](host::FrameView frame) {
        auto word = [&frame](size_t at) {
            return uint16_t(frame.bytes[at] | frame.bytes[at + 1] << 8);
        };
        constexpr size_t source_offset = 2, type_offset = 4;
        if (word(type_offset) < NODE_FIRST_SYSTEM_TYPE)
            events_by_node[word(source_offset)]++;
    });

    // Steps are counted, then turned into seconds, so that a robot that
    // stayed all along gets exactly the run's duration.
    const size_t robots = simulation.robot_count();
    std::vector<uint64_t> dangerous_steps(robots, 0);
    std::vector<std::vector<uint64_t>> area_steps(robots,
                                                  std::vector<uint64_t>(arena.areas.size(), 0));
    // A duration of whole steps must not gain one from rounding.
    constexpr double rounding_slack = 1e-9;
    const uint64_t steps =
      uint64_t(std::ceil(seconds / arena::EnkiWorld::step_seconds - rounding_slack));
    for (uint64_t step = 0; step < steps; step++) {
        simulation.step();
        for (size_t robot = 0; robot < robots; robot++) {
            arena::Pose pose = simulation.world().pose(robot);
            int area = area_at(arena, pose.x, pose.y);
            if (area < 0)
                continue;
            area_steps[robot][size_t(area)]++;
            if (dangerous[size_t(area)])
                dangerous_steps[robot]++;
        }
    }

    RunResult result;
    result.condition = condition;
    result.seed = seed;
    result.seconds = double(steps) * arena::EnkiWorld::step_seconds;
    for (size_t robot = 0; robot < robots; robot++) {
        RobotTimes times;
        times.node_id = arena.robots[robot].node_id;
        times.seconds_on_dangerous =
          double(dangerous_steps[robot]) * arena::EnkiWorld::step_seconds;
        for (uint64_t count : area_steps[robot])
            times.seconds_on_area.push_back(double(count) * arena::EnkiWorld::step_seconds);
        times.events_emitted = events_by_node[times.node_id];
        result.robots.push_back(times);
    }
    return result;
}

std::vector<uint16_t> compile_for_epuck(const std::string &path)
{
    ProgramFile program = read_program_file(path);
    if (program.node_name != EPUCK_NAME) {
        // A project may hold several nodes: take the e-puck's when there is one.
        try {
            program = read_program_file(path, EPUCK_NAME);
        } catch (const std::runtime_error &) {
        }
    }
    std::string error_text;
    CompileResult result = compile_program_file(program, epuck_target(), error_text);
    if (!result.ok)
        throw std::runtime_error(error_text);
    return result.bytecode;
}

} // namespace aseba::experiment
