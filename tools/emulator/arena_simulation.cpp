// The arena's lockstep scheduler (see arena_simulation.hpp).

#include "arena_simulation.hpp"

#include <algorithm>
#include <cmath>

#include "robot_memory.hpp"

namespace aseba::arena
{
namespace
{

constexpr uint32_t milliseconds_per_step = uint32_t(EnkiWorld::step_seconds * 1000 + 0.5);
// Firmware passes per robot and millisecond at most. The node takes one
// frame a pass and every robot sees every frame, so while a group is flashed
// each robot skips the bootloader frames meant for the others: 32 a
// millisecond keeps up with the tools. Bounded so that a robot flooding the
// bus cannot stall time; an idle robot needs one pass.
constexpr int polls_per_tick = 32;

void hold_output(void *context, const uint8_t *bytes, uint16_t count)
{
    auto *held = static_cast<ArenaSimulation::HeldOutput *>(context);
    held->bytes.insert(held->bytes.end(), bytes, bytes + count);
}

} // namespace

ArenaSimulation::ArenaSimulation(const Arena &arena,
                                 uint32_t seed,
                                 const std::vector<uint16_t> &bytecode,
                                 const std::function<void(host_robot &)> &prepare,
                                 unsigned threads)
  : world_(arena, seed)
  , workers_(threads)
  , run_robots_([this](size_t begin, size_t end) { run_robots(begin, end); })
{
    // Enki's sensing pass on the firmware's threads, which wait meanwhile.
    world_.set_parallel_for([this](size_t count, const std::function<void(size_t, size_t)> &work) {
        workers_.run(count, work);
    });
    for (size_t i = 0; i < arena.robots.size(); i++) {
        auto robot = std::make_unique<host_robot>();
        uint16_t node_id = arena.robots[i].node_id;
        host_robot_init(
          robot.get(),
          node_id == RobotPlacement::node_id_from_selector ? HOST_ROBOT_NODE_ID_AT_BOOT : node_id,
          nullptr,
          nullptr);
        host_board_set_world(&robot->board, world_.world_of(i));
        // Its selector now stands where the arena put it.
        host_robot_update_node_id(robot.get());
        network_.attach(&robot->board);
        host::power_on(*robot, prepare, bytecode);
        auto held = std::make_unique<HeldOutput>();
        held->output = robot->board.link_output;
        held->context = robot->board.link_context;
        robot->board.link_output = hold_output;
        robot->board.link_context = held.get();
        held_outputs_.push_back(std::move(held));
        robots_.push_back(std::move(robot));
    }
}

ArenaSimulation::~ArenaSimulation() = default;

void ArenaSimulation::run_robots(size_t begin, size_t end)
{
    for (size_t i = begin; i < end; i++) {
        host_robot *robot = robots_[i].get();
        host_board_set_time(&robot->board, milliseconds_);
        for (int poll = 0; poll < polls_per_tick; poll++)
            if (!host_robot_poll(robot))
                break;
    }
}

void ArenaSimulation::step()
{
    for (uint32_t tick = 0; tick < milliseconds_per_step; tick++) {
        milliseconds_++;
        workers_.run(robots_.size(), run_robots_);
        for (auto &held : held_outputs_) {
            for (size_t sent = 0; sent < held->bytes.size();) {
                uint16_t count = uint16_t(std::min<size_t>(held->bytes.size() - sent, UINT16_MAX));
                held->output(held->context, held->bytes.data() + sent, count);
                sent += count;
            }
            held->bytes.clear();
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

host_robot &ArenaSimulation::robot(size_t index)
{
    return *robots_.at(index);
}

firmware_state &ArenaSimulation::firmware(size_t index)
{
    return robots_.at(index)->firmware;
}

hal_board &ArenaSimulation::board(size_t index)
{
    return robots_.at(index)->board;
}

uint16_t ArenaSimulation::node_id(size_t index) const
{
    return robots_.at(index)->node_id;
}

void ArenaSimulation::set_selector(size_t index, uint16_t position)
{
    world_.set_selector(index, position);
}

void ArenaSimulation::press_remote_key(const std::vector<size_t> &indices,
                                       uint8_t address,
                                       uint8_t command)
{
    // A remote flips its toggle bit at each new key press, so that a
    // receiver tells a second press from a held key.
    remote_toggle_ ^= 1u;
    Rc5Frame frame{ remote_toggle_, address, command };
    for (size_t index : indices)
        world_.send_rc5(index, frame);
}

} // namespace aseba::arena
