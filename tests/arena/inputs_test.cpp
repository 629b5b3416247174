// The arena's selector, remote control and battery, read by the real
// drivers and firmware from the simulated pins: selector positions and the
// node id the chip derives from them (hardware §6.6), RC5 frames against the
// RC5 specification and decoded into `rc5`, and the battery's low line
// against the crossing times the documented model gives
// (docs/arena-format.md).

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "arena_test_support.hpp"

extern "C" {
#include "boards/epuck_host/epuck_host_config.h"
}

using namespace aseba::arena;
using arena_test::compile;
using arena_test::variables;

namespace
{

Arena robots_in_a_row(size_t count)
{
    Arena arena;
    for (size_t i = 0; i < count; i++)
        arena.robots.push_back({ uint16_t(i + 1), 20 + 20 * double(i), 50, 0 });
    return arena;
}

constexpr uint16_t from_selector = RobotPlacement::node_id_from_selector;

} // namespace

TEST(Selector, FirmwareReadsThePositionFromThePins)
{
    Arena arena = robots_in_a_row(2);
    arena.robots[0].selector = 5;
    arena.robots[1].selector = 15;
    ArenaSimulation simulation(arena, 1, {});
    simulation.run_for(0.05);
    EXPECT_EQ(variables(simulation, 0).selector[0], 5);
    EXPECT_EQ(variables(simulation, 1).selector[0], 15);
    for (uint16_t position : { 0, 9, 10, 3 }) {
        simulation.set_selector(1, position);
        simulation.run_for(0.01);
        EXPECT_EQ(variables(simulation, 1).selector[0], position);
    }
    EXPECT_EQ(variables(simulation, 0).selector[0], 5) << "the other robot's selector moved";
}

// A robot without a stored node id answers as (selector & 7) + 1 (hardware
// §6.6), read at each start: turning the selector takes effect at the next
// reset.
TEST(Selector, SetsTheNodeIdOfARobotWithoutOneAtEachStart)
{
    Arena arena = robots_in_a_row(3);
    arena.robots[0].node_id = from_selector;
    arena.robots[0].selector = 5;
    arena.robots[1].node_id = from_selector;
    arena.robots[1].selector = 10;
    arena.robots[2].node_id = 9; // stored: the selector does not matter
    arena.robots[2].selector = 3;
    ArenaSimulation simulation(arena, 1, {});
    simulation.run_for(0.05);
    EXPECT_EQ(simulation.node_id(0), 6);
    EXPECT_EQ(variables(simulation, 0).id[0], 6);
    EXPECT_EQ(variables(simulation, 1).id[0], 3);
    EXPECT_EQ(variables(simulation, 2).id[0], 9);

    simulation.set_selector(0, 2);
    simulation.set_selector(2, 0);
    simulation.run_for(0.05);
    EXPECT_EQ(variables(simulation, 0).id[0], 6) << "the id changed without a reset";
    for (size_t robot : { 0, 2 })
        host_robot_reset(&simulation.robot(robot));
    // The bootloader waits a second for a host before the firmware starts.
    simulation.run_for(1.5);
    ASSERT_EQ(simulation.robot(0).mode, HOST_ROBOT_IN_APPLICATION);
    EXPECT_EQ(simulation.node_id(0), 3);
    EXPECT_EQ(variables(simulation, 0).id[0], 3);
    EXPECT_EQ(variables(simulation, 2).id[0], 9);
}

// RC5 (Philips): two start bits, toggle, 5 address and 6 command bits, most
// significant first, each 64 periods of 36 kHz, a 1 being a half bit without
// carrier then one with; the receiver's output is low with the carrier. So
// toggle 1, address 0 (TV), command 12 (standby) is 11 1 00000 001100, and
// its line, half bit by half bit (H high, L low):
TEST(RemoteControl, FrameOnTheReceiverLineFollowsTheRc5Specification)
{
    const std::string expected = "HLHL"
                                 "HL"
                                 "LHLHLHLHLH"
                                 "LHLHHLHLLHLH";
    RemoteReceiver receiver;
    const uint64_t start = 1000000;
    receiver.send({ 1, 0, 12 }, start);
    const double half_bit = 32.0 / 36000; // s
    std::string line;
    for (unsigned half = 0; half < 28; half++) {
        double middle = (half + 0.5) * half_bit;
        line += receiver.level(start + uint64_t(middle * HOST_CYCLES_PER_SECOND)) ? 'H' : 'L';
    }
    EXPECT_EQ(line, expected);
    EXPECT_TRUE(receiver.level(start - 1)) << "idle before";
    EXPECT_TRUE(receiver.level(start + uint64_t(28.01 * half_bit * HOST_CYCLES_PER_SECOND)))
      << "idle after";
    // The first change is the falling edge in the middle of the first start
    // bit, where the robot's decoder starts.
    EXPECT_EQ(receiver.next_change(start), start + rc5_half_bit_cycles(1));
    EXPECT_NEAR(double(rc5_half_bit_cycles(28)) / HOST_CYCLES_PER_SECOND, 14 * 64 / 36000.0, 1e-6);
}

TEST(RemoteControl, KeyPressesReachTheRobotsTheyArePointedAt)
{
    ArenaSimulation simulation(robots_in_a_row(3), 1, {});
    simulation.run_for(0.05);
    simulation.press_remote_key({ 1 }, 0, 12);
    simulation.run_for(0.05); // a frame lasts 25 ms
    EXPECT_EQ(variables(simulation, 0).rc5[0], 0);
    EXPECT_EQ(variables(simulation, 1).rc5[0], 12);
    EXPECT_EQ(variables(simulation, 2).rc5[0], 0);
    simulation.press_remote_key({ 0, 1, 2 }, 5, 33);
    simulation.run_for(0.05);
    for (size_t robot = 0; robot < 3; robot++)
        EXPECT_EQ(variables(simulation, robot).rc5[0], 33) << "robot " << robot + 1;
}

TEST(RemoteControl, PressesInQuickSuccessionComeOneAfterTheOther)
{
    // The second frame waits for the repetition period (113.8 ms) after the
    // first one's start.
    ArenaSimulation simulation(robots_in_a_row(1), 1, {});
    simulation.run_for(0.05);
    simulation.press_remote_key({ 0 }, 0, 16);
    simulation.press_remote_key({ 0 }, 0, 17);
    simulation.run_for(0.05);
    EXPECT_EQ(variables(simulation, 0).rc5[0], 16);
    simulation.run_for(0.1);
    EXPECT_EQ(variables(simulation, 0).rc5[0], 17);
}

// The documented model: 120 mA always, 150 mA more per powered motor; the
// low line falls below 3.4 V, at 5 % of the charge. With a 10 mAh battery, a
// robot spinning (both motors) from 10 % crosses after 0.05 x 10 mAh /
// 420 mA = 4.29 s, and a still robot from 6 % after 0.01 x 10 / 120 = 3.0 s.
TEST(Battery, LowLineFallsWhenTheModelSaysItShould)
{
    Arena arena = robots_in_a_row(2);
    arena.battery = { .capacity_mah = 10, .idle_ma = 120, .motor_ma = 150 };
    arena.robots[0].selector = 1; // spins
    arena.robots[0].battery_charge = 0.10;
    arena.robots[1].battery_charge = 0.06;
    ArenaSimulation simulation(arena, 1, compile("tests/arena/data/spin-on-selector.aesl"));
    const double expected[2] = { 0.05 * 10 / 420 * 3600, 0.01 * 10 / 120.0 * 3600 };
    double crossed[2] = { -1, -1 };
    while (simulation.seconds() < 5) {
        simulation.step();
        for (size_t robot = 0; robot < 2; robot++)
            if (crossed[robot] < 0 && variables(simulation, robot).battery[0] == 0)
                crossed[robot] = simulation.seconds();
    }
    for (size_t robot = 0; robot < 2; robot++) {
        std::printf("    robot %zu: battery low at %.2f s, the model says %.2f s\n",
                    robot + 1,
                    crossed[robot],
                    expected[robot]);
        // The firmware samples the line at once; the charge moves by steps.
        EXPECT_NEAR(crossed[robot], expected[robot], 0.03) << "robot " << robot + 1;
    }
}

TEST(Battery, VoltageCurveIsTheDocumentedOne)
{
    EXPECT_DOUBLE_EQ(battery_volts(1), 4.2);
    EXPECT_DOUBLE_EQ(battery_volts(0.05), 3.4);
    EXPECT_DOUBLE_EQ(battery_volts(0), 3.0);
    EXPECT_NEAR(battery_volts(0.55), 3.875, 1e-12); // halfway between 20 % and 90 %
    Battery full(BatteryModel{}, 1);
    EXPECT_FALSE(full.low());
    // The default cell (1350 mAh) with both motors powered: 95 % in
    // 0.95 x 1350 / 420 h, 3.05 h.
    double hours = 0.95 * 1350 / 420;
    full.drain(hours * 3600 * 0.999, 2);
    EXPECT_FALSE(full.low());
    full.drain(hours * 3600 * 0.002, 2);
    EXPECT_TRUE(full.low());
}
