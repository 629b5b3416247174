// The simulated arena: e-pucks running the real firmware on host boards, in
// one Enki world, joined by one Aseba network. Time is simulated and
// advances in lockstep: each step moves every board's clock by the world's
// step, a millisecond at a time with a firmware pass and a network pass
// after each, then advances the physics. Nothing depends on the wall clock,
// so the same arena and seed give the same run, bit for bit, as long as no
// tool sends frames.
//
// The robots' firmware may run on several threads: in a millisecond each
// robot only reads the world and its own board, and what it sends waits
// until every robot has run, then goes to the network in robot order, as it
// would from one thread. The run is the same whatever the thread count.

#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "arena_file.hpp"
#include "enki_world.hpp"
#include "network.hpp"
#include "worker_pool.hpp"

extern "C" {
#include "ports/host/host_robot.h"
}

namespace aseba::arena
{

class ArenaSimulation
{
  public:
    // Builds the world and powers each robot on with its node id (or, for a
    // robot without one, the id its selector gives, as on the chip),
    // `prepare` and `bytecode` as host::power_on does (robot_memory.hpp);
    // the firmware runs on `threads` threads (the caller's included).
    ArenaSimulation(const Arena &arena,
                    uint32_t seed,
                    const std::vector<uint16_t> &bytecode,
                    const std::function<void(host_robot &)> &prepare = {},
                    unsigned threads = 1);
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
    // Threads the firmware runs on.
    unsigned threads() const
    {
        return workers_.threads();
    }
    host_robot &robot(size_t index);
    firmware_state &firmware(size_t index);
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

    // The node id robot `index` answers to since it last started.
    uint16_t node_id(size_t index) const;

    // Turns robot `index`'s selector (see EnkiWorld::set_selector).
    void set_selector(size_t index, uint16_t position);

    // A key press on the remote control, seen by the robots `indices`: RC5
    // `command` for device `address`, with the toggle bit flipped since the
    // last press. Throws std::out_of_range for an index without a robot.
    void press_remote_key(const std::vector<size_t> &indices, uint8_t address, uint8_t command);

    // Where a robot's link output goes while the robots run: held, then
    // passed to the network's output in robot order.
    struct HeldOutput {
        void (*output)(void *context, const uint8_t *bytes, uint16_t count) = nullptr;
        void *context = nullptr;
        std::vector<uint8_t> bytes;
    };

  private:
    // One millisecond of firmware for robots begin..end.
    void run_robots(size_t begin, size_t end);

    EnkiWorld world_;
    host::Network network_;
    std::vector<std::unique_ptr<host_robot>> robots_;
    std::vector<std::unique_ptr<HeldOutput>> held_outputs_;
    WorkerPool workers_;
    std::function<void(size_t, size_t)> run_robots_;
    uint32_t milliseconds_ = 0;
    uint8_t remote_toggle_ = 0;
};

} // namespace aseba::arena
