// An e-puck of the arena on the simulated dsPIC30F6014A (tools/emulator/dspic30_robot.hpp):
// the factory image that `make dspic30` links, on a board fed by the same
// world model as the host-built robot of epuck-emu. Each check puts the same
// robot in the same arena (same seed) twice, once on the host board
// (ArenaSimulation), once on the chip, and compares what the firmware sees
// and does: the host robot's values are the expectation, with physical
// facts besides (a wall ahead reflects, an upright robot feels 1 g, a free
// robot drives forward).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <string>
#include <optional>
#include <vector>

#include "tests/arena/arena_test_support.hpp"
#include "tools/client/messages.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"
#include "tools/emulator/dspic30_arena.hpp"
#include "tools/emulator/dspic30_robot.hpp"

extern "C" {
#include "robots/epuck/epuck_variables.h"
}

namespace
{

using aseba::arena::Arena;
using aseba::arena::ArenaSimulation;
using aseba::arena::default_arena;
using aseba::arena::Dspic30Robot;
using aseba::arena::EnkiWorld;
using aseba::arena::Pose;
namespace client = aseba::client;

constexpr uint32_t seed = 7;
constexpr uint64_t step_cycles = uint64_t(EnkiWorld::step_seconds * HOST_CYCLES_PER_SECOND + 0.5);
constexpr double pi = 3.14159265358979323846;

// The VM's variable index of a named variable (the named ones come first,
// in the struct's order).
#define VARIABLE_INDEX(member) uint16_t(offsetof(epuck_named_variables, member) / sizeof(int16_t))

// A dsPIC robot in a world of its own, stepped in lockstep as ArenaSimulation
// steps its robots: 10 ms of firmware, then the world's step.
class ChipInArena
{
  public:
    explicit ChipInArena(const Arena &arena)
      : world_(arena, seed)
      , robot_(aseba::dspic30::read_intel_hex_file(DSPIC30_FACTORY_HEX), *world_.world_of(0))
    {
    }

    void step()
    {
        auto outcome = robot_.run_until(world_.cycles() + step_cycles);
        ASSERT_EQ(outcome, aseba::dspic30::Outcome::cycle_limit);
        std::vector<uint8_t> bytes = robot_.take_output();
        frames_.feed(bytes.data(), bytes.size());
        world_.step();
    }
    void run_for(double seconds)
    {
        for (int i = 0; i < int(std::lround(seconds / EnkiWorld::step_seconds)); i++)
            step();
    }
    double seconds() const
    {
        return double(world_.cycles()) / HOST_CYCLES_PER_SECOND;
    }

    void send(const client::Message &message)
    {
        std::vector<uint8_t> bytes = client::serialize_frame(client::encode(message));
        robot_.receive(bytes.data(), bytes.size());
    }
    // The next frame the robot sent that `wanted` accepts, within `seconds`.
    template<typename Wanted>
    std::optional<client::Frame> wait_for(double seconds, Wanted wanted)
    {
        for (double end = this->seconds() + seconds; this->seconds() < end; step())
            while (std::optional<client::Frame> frame = frames_.next())
                if (wanted(*frame))
                    return frame;
        return std::nullopt;
    }

    // The node id the firmware answers LIST_NODES with, once it runs.
    uint16_t node_id()
    {
        send(client::ListNodes{});
        auto present = wait_for(
          0.5, [](const client::Frame &frame) { return frame.type == NODE_MSG_NODE_PRESENT; });
        EXPECT_TRUE(present.has_value()) << "no NODE_PRESENT at " << seconds() << " s";
        return present ? present->source : 0;
    }

    std::vector<int16_t> variables(uint16_t node, uint16_t start, uint16_t length)
    {
        send(client::GetVariables{ node, start, length });
        auto reply = wait_for(0.5, [&](const client::Frame &frame) {
            return frame.type == NODE_MSG_VARIABLES && frame.source == node;
        });
        if (!reply) {
            ADD_FAILURE() << "no VARIABLES for " << start << " at " << seconds() << " s";
            return std::vector<int16_t>(length, 0);
        }
        auto message = std::get<client::Variables>(client::decode(*reply));
        EXPECT_EQ(message.start, start);
        return message.values;
    }

    void load_and_run(uint16_t node, const std::vector<uint16_t> &bytecode)
    {
        for (size_t at = 0; at < bytecode.size(); at += client::MAX_BYTECODE_CHUNK_WORDS) {
            size_t end = std::min(bytecode.size(), at + client::MAX_BYTECODE_CHUNK_WORDS);
            send(client::SetBytecode{
              node,
              uint16_t(at),
              std::vector<uint16_t>(bytecode.begin() + long(at), bytecode.begin() + long(end)) });
        }
        send(client::NodeCommand{ NODE_MSG_RUN, node });
    }

    EnkiWorld &world()
    {
        return world_;
    }
    Dspic30Robot &robot()
    {
        return robot_;
    }

  private:
    EnkiWorld world_;
    Dspic30Robot robot_;
    client::FrameAssembler frames_;
};

// What a still robot's firmware reads, by the VM's variables.
struct Readings {
    std::vector<int16_t> prox, ambient, acc, red, green, blue;
};

Arena one_robot_arena()
{
    return default_arena(1);
}

// Both robots stand where the arena puts them, clear of everything, while
// the firmware calibrates its proximity sensors (2 s from the application's
// start; the chip's starts after its bootloader's second), then stand at
// the pose under test for a while before they are read, at the same step of
// their worlds.
constexpr double calibration_seconds = 3.5;
constexpr double posed_seconds = 0.5;

Readings host_still_readings(const Pose &pose)
{
    ArenaSimulation simulation(one_robot_arena(), seed, {});
    simulation.run_for(calibration_seconds);
    simulation.world().place(0, pose);
    simulation.run_for(posed_seconds);
    const epuck_named_variables &named = simulation.firmware(0).variables.named;
    auto words = [](const int16_t *from, size_t count) {
        return std::vector<int16_t>(from, from + count);
    };
    return { words(named.prox, 8),     words(named.ambient, 8),    words(named.acc, 3),
             words(named.cam_red, 60), words(named.cam_green, 60), words(named.cam_blue, 60) };
}

Readings chip_still_readings(const Pose &pose)
{
    ChipInArena chip(one_robot_arena());
    chip.run_for(calibration_seconds);
    chip.world().place(0, pose);
    chip.run_for(posed_seconds);
    uint16_t node = chip.node_id();
    Readings readings;
    readings.prox = chip.variables(node, VARIABLE_INDEX(prox), 8);
    readings.ambient = chip.variables(node, VARIABLE_INDEX(ambient), 8);
    readings.acc = chip.variables(node, VARIABLE_INDEX(acc), 3);
    readings.red = chip.variables(node, VARIABLE_INDEX(cam_red), 60);
    readings.green = chip.variables(node, VARIABLE_INDEX(cam_green), 60);
    readings.blue = chip.variables(node, VARIABLE_INDEX(cam_blue), 60);
    return readings;
}

// Facing the +x wall, its front 1 cm from it (the body's radius is 3.7 cm),
// half-way up.
Pose facing_the_wall()
{
    Arena arena = one_robot_arena();
    return { arena.width - 3.7 - 1.0, arena.height / 2, 0 };
}

TEST(Dspic30ArenaRobot, ProximityAndAmbientAreTheHostRobots)
{
    Readings host = host_still_readings(facing_the_wall());
    Readings chip = chip_still_readings(facing_the_wall());
    // Enki's e-puck read 1225 at 1 cm (tests/arena's calibration); nothing
    // reflects behind.
    const double at_one_centimetre = 1225;
    EXPECT_NEAR(host.prox[0], at_one_centimetre, 0.2 * at_one_centimetre);
    EXPECT_NEAR(host.prox[7], at_one_centimetre, 0.2 * at_one_centimetre);
    EXPECT_LT(host.prox[3], 30);
    EXPECT_LT(host.prox[4], 30);
    for (size_t i = 0; i < 8; i++) {
        // Same world, same seed, same step, the same 12-bit conversions;
        // but each reading carries the world's IR noise (10 counts sd, drawn
        // each step), which the two firmwares sample at their own moments
        // and calibrated over windows a second apart: the difference of two
        // such readings stays within 3 sd of it (42 counts).
        const double noise_sd = 10;
        EXPECT_NEAR(chip.prox[i], host.prox[i], 3 * noise_sd * std::sqrt(2.0))
          << "prox[" << i << "]";
        EXPECT_EQ(chip.ambient[i], host.ambient[i]) << "ambiant[" << i << "]";
    }
}

TEST(Dspic30ArenaRobot, AccelerometerFeelsOneGUprightAsTheHostRobot)
{
    Readings host = host_still_readings(facing_the_wall());
    Readings chip = chip_still_readings(facing_the_wall());
    for (size_t axis = 0; axis < 3; axis++)
        EXPECT_EQ(chip.acc[axis], host.acc[axis]) << "acc[" << axis << "]";
    // Upright and still: no acceleration in the plane, gravity on z.
    EXPECT_EQ(host.acc[0], 0);
    EXPECT_EQ(host.acc[1], 0);
    EXPECT_GT(host.acc[2], 500);
}

TEST(Dspic30ArenaRobot, CameraSeesWhatTheHostRobotSees)
{
    // Robot 1 of the default arena faces outward from the centre, the green
    // disc ahead of it.
    Arena arena = one_robot_arena();
    const auto &placed = arena.robots[0];
    Pose pose{ placed.x, placed.y, placed.heading_degrees * pi / 180 };
    Readings host = host_still_readings(pose);
    Readings chip = chip_still_readings(pose);
    int lit = 0;
    for (size_t i = 0; i < 60; i++) {
        EXPECT_EQ(chip.red[i], host.red[i]) << "camR[" << i << "]";
        EXPECT_EQ(chip.green[i], host.green[i]) << "camG[" << i << "]";
        EXPECT_EQ(chip.blue[i], host.blue[i]) << "camB[" << i << "]";
        lit += host.red[i] + host.green[i] + host.blue[i] > 0;
    }
    // Not a black camera: the floor and the disc are seen.
    EXPECT_GT(lit, 30);
}

// The link keeps up with what other robots send: their frames (the
// network relays every robot's frames to the others) arrive back to back at
// 115,200 baud for 1.6 s, many times the firmware's 522-byte receive ring,
// while the camera is read (some 30 of its frames) and while the robot
// sends its own description (65 frames, asked for just before): the whole
// description comes out, and a request behind the traffic is answered. Two
// robots listed by `aseba nodes` (each asked for its description at once)
// did neither (docs/dspic30-sim.md): the main loop waited for the camera's
// rows, then for the whole description to be sent, the ADC's interrupt
// took longer than the time between two scans, and bytes were lost, after
// which every frame was misread.
TEST(Dspic30ArenaRobot, LinkKeepsUpWithTrafficWhileTheCameraIsReadAndTheDescriptionSent)
{
    ChipInArena chip(one_robot_arena());
    chip.run_for(2.0); // past the bootloader's wait for a host (1 s)
    const uint16_t node = chip.node_id();
    ASSERT_NE(node, 0);
    // 700 events of 10 arguments from node 2: 18,200 bytes.
    constexpr uint16_t other_node = 2, event = 1, arguments = 10;
    std::vector<uint8_t> traffic;
    for (int frame = 0; frame < 700; frame++) {
        for (uint16_t word : { uint16_t(2 * arguments), other_node, event })
            traffic.insert(traffic.end(), { uint8_t(word & 0xFF), uint8_t(word >> 8) });
        for (uint16_t argument = 0; argument < arguments; argument++)
            traffic.insert(traffic.end(), { uint8_t(frame), uint8_t(argument) });
    }
    chip.send(client::GetDescription{ node });
    chip.robot().receive(traffic.data(), traffic.size());
    const double traffic_end = chip.seconds() + 1.6; // 18,200 bytes of 10 bits at 115,200 baud

    // DESCRIPTION announces the counts of the frames that follow it.
    auto description = chip.wait_for(
      1.0, [](const client::Frame &frame) { return frame.type == NODE_MSG_DESCRIPTION; });
    ASSERT_TRUE(description.has_value());
    const auto counts = std::get<client::Description>(client::decode(*description));
    const int expected =
      counts.named_variables_count + counts.local_events_count + counts.native_functions_count;
    int described = 0;
    chip.wait_for(2.0, [&](const client::Frame &frame) {
        described += frame.type == NODE_MSG_NAMED_VARIABLE_DESCRIPTION ||
                     frame.type == NODE_MSG_LOCAL_EVENT_DESCRIPTION ||
                     frame.type == NODE_MSG_NATIVE_FUNCTION_DESCRIPTION;
        return described == expected;
    });
    EXPECT_EQ(described, expected);
    EXPECT_EQ(expected, 64); // 23 named variables, 4 local events, 37 natives
    chip.run_for(traffic_end - chip.seconds());
    EXPECT_EQ(chip.node_id(), node) << "after the traffic, at " << chip.seconds() << " s";
}

// A TV remote's key reaches the chip as on a robot (§3.9): the receiver's
// line on RF6 falls at the frame's first bit, INT0 (falling edge) starts
// the firmware's RC5 sampling, and `rc5` holds the command sent.
TEST(Dspic30ArenaRobot, RemoteKeyReachesTheFirmwareThroughInt0)
{
    ChipInArena chip(one_robot_arena());
    chip.run_for(2.0); // past the bootloader's wait for a host (1 s)
    const uint16_t node = chip.node_id();
    ASSERT_NE(node, 0);
    EXPECT_EQ(chip.variables(node, VARIABLE_INDEX(rc5), 1)[0], 0);
    // Every command bit both ways, the toggle bit flipped at each key.
    uint8_t toggle = 0;
    for (uint8_t command : { 37, 12, 63, 42, 21, 1 }) {
        aseba::arena::Rc5Frame frame;
        frame.toggle = toggle ^= 1;
        frame.command = command;
        chip.world().send_rc5(0, frame);
        chip.run_for(0.1); // 14 bits of 1.778 ms
        EXPECT_EQ(chip.variables(node, VARIABLE_INDEX(rc5), 1)[0], command);
    }
}

TEST(Dspic30ArenaRobot, LedsVariableLightsTheRingAsOnTheHostRobot)
{
    const std::vector<int16_t> pattern = { 1, 0, 0, 32, 0, 7, 1, 0 };
    ArenaSimulation host(one_robot_arena(), seed, {});
    host.run_for(1.5);
    std::copy(pattern.begin(), pattern.end(), host.firmware(0).variables.named.leds);
    host.run_for(0.1);

    ChipInArena chip(one_robot_arena());
    chip.run_for(1.5);
    uint16_t node = chip.node_id();
    chip.send(client::SetVariables{ node, VARIABLE_INDEX(leds), pattern });
    chip.run_for(0.1);
    for (size_t led = 0; led < pattern.size(); led++) {
        epuck_pin pin = epuck_pin(EPUCK_PIN_LED_0 + led);
        // A non-zero value lights the LED (the variable's meaning).
        EXPECT_EQ(host.board(0).outputs[pin], pattern[led] != 0) << "host LED " << led;
        EXPECT_EQ(chip.robot().output(pin), pattern[led] != 0) << "chip LED " << led;
    }
}

TEST(Dspic30ArenaRobot, PaperAnnexDrivesAsOnTheHostRobot)
{
    const std::vector<uint16_t> annex = arena_test::compile("examples/paper-annex.aesl");
    Arena arena = one_robot_arena();
    const double program_seconds = 2.5;

    ArenaSimulation host(arena, seed, annex);
    Pose host_start = host.world().pose(0);
    host.run_for(program_seconds);
    Pose host_end = host.world().pose(0);

    ChipInArena chip(arena);
    chip.run_for(1.5); // the bootloader's second, the application starting
    uint16_t node = chip.node_id();
    chip.world().place(0, host_start);
    chip.load_and_run(node, annex);
    chip.run_for(program_seconds);
    Pose chip_end = chip.world().pose(0);

    double host_dx = host_end.x - host_start.x, host_dy = host_end.y - host_start.y;
    double chip_dx = chip_end.x - host_start.x, chip_dy = chip_end.y - host_start.y;
    double host_moved = std::hypot(host_dx, host_dy);
    // The annex drives at 1000 steps/s, 12.8 cm/s, where nothing is near.
    EXPECT_GT(host_moved, 0.7 * 12.8 * program_seconds);
    // The chip's robot went as far the same way; it starts a little later
    // (its frames take their time on the UART).
    EXPECT_NEAR(std::hypot(chip_dx, chip_dy), host_moved, 0.15 * host_moved);
    EXPECT_NEAR(std::hypot(chip_dx - host_dx, chip_dy - host_dy), 0, 0.15 * host_moved);
    // The program's speeds reached the VM as the host robot's.
    std::vector<int16_t> speeds = chip.variables(node, VARIABLE_INDEX(left_speed), 2);
    EXPECT_GT(speeds[0], 0);
    EXPECT_GT(speeds[1], 0);
}

// `epuck-emu --dspic30 IMAGE --load FILE`: the arena sends the program to
// every chip once its firmware runs (Dspic30Arena::load_at_start), and each
// robot drives: the paper's controller moves all three of the default
// arena's robots (each at least half of 12.8 cm/s over the 2.5 s after the
// program's start, whatever it meets).
TEST(Dspic30ArenaRobot, ArenaLoadsTheProgramIntoEveryChip)
{
    aseba::arena::Dspic30Arena arena(
      default_arena(3), seed, aseba::dspic30::read_intel_hex_file(DSPIC30_FACTORY_HEX));
    arena.load_at_start(arena_test::compile("examples/paper-annex.aesl"));
    while (arena.seconds() < 1.6) // the program is sent at 1.5 s
        arena.step();
    std::vector<Pose> start;
    for (size_t i = 0; i < 3; i++)
        start.push_back(arena.world().pose(i));
    while (arena.seconds() < 4.1)
        arena.step();
    for (size_t i = 0; i < 3; i++) {
        Pose end = arena.world().pose(i);
        EXPECT_GT(std::hypot(end.x - start[i].x, end.y - start[i].y), 0.5 * 12.8 * 2.5)
          << "robot " << i + 1;
    }
}

// The deepest the application's stack goes while the paper's controller
// runs, its description is sent and its variables are read (every
// interrupt of the board going on meanwhile): W15 stays below SPLIM, the
// limit the start-up code sets from the linker's stack region (a stack
// error trap otherwise), and within that region. The depth is printed for
// docs/benchmarks.md (the RAM budget).
TEST(Dspic30ArenaRobot, StackStaysWithinTheLinkersReserve)
{
    const std::vector<uint16_t> annex = arena_test::compile("examples/paper-annex.aesl");
    std::ifstream map(DSPIC30_APPLICATION_MAP);
    ASSERT_TRUE(map) << DSPIC30_APPLICATION_MAP;
    unsigned stack_base = 0, stack_bytes = 0;
    for (std::string line; std::getline(map, line);)
        if (std::sscanf(line.c_str(), "stack %x %x", &stack_base, &stack_bytes) == 2)
            break;
    ASSERT_GT(stack_bytes, 0u) << "no stack region in the map";

    Arena arena = one_robot_arena();
    ChipInArena chip(arena);
    chip.run_for(1.5); // the bootloader's second, the application starting
    uint16_t node = chip.node_id();
    aseba::dspic30::Cpu &cpu = chip.robot().chip().cpu();
    const uint16_t limit = cpu.read_data(0x0020); // SPLIM
    uint16_t deepest = 0;
    cpu.set_trace([&](const aseba::dspic30::Cpu &c) { deepest = std::max(deepest, c.w(15)); });
    chip.load_and_run(node, annex);
    chip.send(client::GetDescription{});
    chip.run_for(1.0);
    chip.variables(node, 0, 100);
    chip.run_for(1.0);
    cpu.set_trace({});

    EXPECT_GE(limit, stack_base);
    EXPECT_LE(limit, stack_base + stack_bytes);
    EXPECT_GT(deepest, stack_base);
    EXPECT_LT(deepest, limit) << "the stack reached SPLIM";
    std::printf("stack: deepest W15 0x%04X, %u of the %u bytes the linker reserves from 0x%04X\n",
                deepest,
                unsigned(deepest - stack_base),
                stack_bytes,
                stack_base);
}

} // namespace
