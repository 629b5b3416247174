// The simulated arena with every robot on its own simulated dsPIC30F6014A
// (dspic30_robot.hpp) running one image (the factory image: bootloader and
// application), in one Enki world and joined by one Aseba network, as
// ArenaSimulation joins host-built robots. Time is simulated and advances in
// lockstep: each world step runs every chip a millisecond at a time, with
// the bytes each one sent passed to the network after each millisecond and
// the network's frames put in its UART1's way, then advances the physics.
//
// A chip keeps no node id of its own until one is stored in its settings:
// the firmware then takes its selector's ((selector & 7) + 1); robot i's
// selector is turned to i at the start (ids 1 to 8; robots beyond share
// them).

#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "arena_file.hpp"
#include "dspic30_robot.hpp"
#include "enki_world.hpp"
#include "network.hpp"

namespace aseba::arena
{

class Dspic30Arena
{
  public:
    // Builds the world and powers each robot's chip on with `image` (PC
    // address -> word).
    Dspic30Arena(const Arena &arena, uint32_t seed, const std::map<uint32_t, uint32_t> &image);
    ~Dspic30Arena();
    Dspic30Arena(const Dspic30Arena &) = delete;
    Dspic30Arena &operator=(const Dspic30Arena &) = delete;

    // Gives every robot `bytecode` (compiled for the e-puck) and runs it, as
    // `aseba load` would, once its firmware has started: the chips keep no
    // program of their own at power-on.
    void load_at_start(std::vector<uint16_t> bytecode);

    // Advances everything by one world step (EnkiWorld::step_seconds).
    // Throws std::runtime_error when a chip stops (a trap storm, an illegal
    // instruction).
    void step();
    // Simulated seconds since the start.
    double seconds() const;
    size_t robot_count() const
    {
        return robots_.size();
    }
    Dspic30Robot &robot(size_t index)
    {
        return robots_.at(index)->chip;
    }
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
    // A chip and the host board that stands for its UART1 on the network:
    // the network writes frames into that board's link, and sends what its
    // output gets.
    struct Member {
        Member(const std::map<uint32_t, uint32_t> &image, const host_world &world)
          : chip(image, world)
        {
        }
        Dspic30Robot chip;
        hal_board link{};
    };

    EnkiWorld world_;
    void load_program();

    host::Network network_;
    std::vector<std::unique_ptr<Member>> robots_;
    uint64_t milliseconds_ = 0;
    std::vector<uint16_t> program_; // for load_at_start, until it is sent
};

} // namespace aseba::arena
