// The simulated arena: e-pucks running the real firmware on host boards, in
// one Enki world, joined by one Aseba network. Time is simulated and
// advances in lockstep: each step moves every board's clock by the world's
// step, a millisecond at a time with a firmware pass and a network pass
// after each, then advances the physics. Nothing depends on the wall clock,
// so the same arena and seed give the same run, bit for bit, as long as no
// tool sends frames.

#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "arena_file.hpp"
#include "enki_world.hpp"
#include "network.hpp"

extern "C" {
#include "firmware/epuck_firmware.h"
}

namespace aseba::arena
{

class ArenaSimulation
{
  public:
    // Builds the world and starts each robot's firmware with its node id;
    // `bytecode` (may be empty) is started on every robot as a stored
    // program would be at boot.
    ArenaSimulation(const Arena &arena, uint32_t seed, const std::vector<uint16_t> &bytecode);
    ~ArenaSimulation();
    ArenaSimulation(const ArenaSimulation &) = delete;
    ArenaSimulation &operator=(const ArenaSimulation &) = delete;

    // Advances everything by one world step (EnkiWorld::step_seconds).
    void step();
    // Advances by whole steps until at least `seconds` more have passed.
    void run_for(double seconds);

    // Simulated seconds since the start.
    double seconds() const;
    size_t robot_count() const;
    epuck_firmware &firmware(size_t index);
    hal_board &board(size_t index);
    EnkiWorld &world()
    {
        return world_;
    }
    // The network joining the robots; listen on it to let tools in.
    host::Network &network()
    {
        return network_;
    }

  private:
    struct Robot {
        hal_board board;
        epuck_firmware firmware;
    };
    EnkiWorld world_;
    host::Network network_;
    std::vector<std::unique_ptr<Robot>> robots_;
    uint32_t milliseconds_ = 0;
};

} // namespace aseba::arena
