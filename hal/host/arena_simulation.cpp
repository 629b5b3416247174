// The arena's lockstep scheduler (see arena_simulation.hpp).

#include "arena_simulation.hpp"

#include <cmath>

namespace aseba::arena
{
namespace
{

constexpr uint32_t milliseconds_per_step = uint32_t(EnkiWorld::step_seconds * 1000 + 0.5);
// Firmware passes per robot and millisecond at most: enough to take a frame
// and answer it, bounded so that a robot flooding the bus cannot stall time.
constexpr int polls_per_tick = 4;

} // namespace

ArenaSimulation::ArenaSimulation(const Arena &arena,
                                 uint32_t seed,
                                 const std::vector<uint16_t> &bytecode)
  : world_(arena, seed)
{
    for (size_t i = 0; i < arena.robots.size(); i++) {
        auto robot = std::make_unique<Robot>();
        host_board_init(&robot->board, nullptr, nullptr);
        host_board_set_world(&robot->board, world_.world_of(i));
        network_.attach(&robot->board);
        epuck_firmware_init(&robot->firmware, &robot->board, arena.robots[i].node_id);
        if (!bytecode.empty())
            epuck_firmware_start_program(
              &robot->firmware, bytecode.data(), uint16_t(bytecode.size()));
        robots_.push_back(std::move(robot));
    }
}

ArenaSimulation::~ArenaSimulation() = default;

void ArenaSimulation::step()
{
    for (uint32_t tick = 0; tick < milliseconds_per_step; tick++) {
        milliseconds_++;
        for (auto &robot : robots_) {
            host_board_set_time(&robot->board, milliseconds_);
            for (int poll = 0; poll < polls_per_tick; poll++)
                if (!epuck_firmware_poll(&robot->firmware))
                    break;
        }
        network_.service(0);
    }
    world_.step();
}

void ArenaSimulation::run_for(double seconds)
{
    uint64_t steps = uint64_t(std::ceil(seconds / EnkiWorld::step_seconds - 1e-9));
    for (uint64_t i = 0; i < steps; i++)
        step();
}

double ArenaSimulation::seconds() const
{
    return milliseconds_ / 1000.0;
}

size_t ArenaSimulation::robot_count() const
{
    return robots_.size();
}

epuck_firmware &ArenaSimulation::firmware(size_t index)
{
    return robots_.at(index)->firmware;
}

hal_board &ArenaSimulation::board(size_t index)
{
    return robots_.at(index)->board;
}

} // namespace aseba::arena
