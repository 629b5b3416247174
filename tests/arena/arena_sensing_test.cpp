// The simulated arena end to end: Enki's world seen through the real
// drivers and firmware (the VM's variables), motor phases moving the
// wheels, emits crossing the network, runs that repeat, and the workarounds
// for the defects of Debian's Enki (../shared/research/enki.md).
//
// Expected values come from the hardware fact sheet (RGB565 scaling, 768
// counts per g, 12.8 cm per 1000 steps) and from Enki's own e-puck as
// measured in the research notes (front IR reading 1225 at a 1 cm gap).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>

#include "arena_test_support.hpp"

using namespace aseba::arena;
using arena_test::compile;
using arena_test::variables;

namespace
{

constexpr double pi = 3.14159265358979323846;
constexpr double arena_side = 100;
constexpr double body_radius = 3.7;
// Long enough for the boot calibration of proximity (100 sets at ~63 Hz)
// and accelerometer (hardware §6.6).
constexpr double calibration_seconds = 2;

Arena empty_arena(Color floor = { 0.2, 0.2, 0.2 })
{
    Arena arena;
    arena.width = arena_side;
    arena.height = arena_side;
    arena.floor_color = floor;
    arena.robots = { { 1, arena_side / 2, arena_side / 2, 0 } };
    return arena;
}

void set_wheels(ArenaSimulation &simulation, int16_t left, int16_t right)
{
    variables(simulation).left_speed[0] = left;
    variables(simulation).right_speed[0] = right;
}

double mean(const int16_t *values, size_t count)
{
    return std::accumulate(values, values + count, 0.0) / double(count);
}

// A still robot 1 cm from the wall on its front (heading 0 faces +x).
Pose facing_wall(double gap)
{
    return { arena_side - body_radius - gap, arena_side / 2, 0 };
}

} // namespace

TEST(ArenaSensing, FrontSensorsReadTheWallAhead)
{
    ArenaSimulation simulation(empty_arena(), 1, {});
    simulation.run_for(calibration_seconds);
    simulation.world().place(0, facing_wall(1));
    simulation.run_for(0.1);
    const int16_t *prox = variables(simulation).prox;
    // Enki's e-puck read 1225 at 1 cm; calibration removed the noise floor.
    const double expected = 1225;
    EXPECT_NEAR(prox[0], expected, 0.2 * expected);
    EXPECT_NEAR(prox[7], expected, 0.2 * expected);
    for (int side : { 2, 3, 4, 5 })
        EXPECT_LT(prox[side], 30) << "sensor " << side;
}

TEST(ArenaSensing, RightSensorReadsAWallOnTheRight)
{
    ArenaSimulation simulation(empty_arena(), 1, {});
    simulation.run_for(calibration_seconds);
    // Facing +y with the +x wall 1 cm to the right.
    simulation.world().place(0, { arena_side - body_radius - 1, arena_side / 2, pi / 2 });
    simulation.run_for(0.1);
    const int16_t *prox = variables(simulation).prox;
    EXPECT_GT(prox[2], 500);
    // Sensors 1 (-45°) and 0 (-18°) see the wall ever more at a slant and
    // from further; the left side sees nothing.
    EXPECT_GT(prox[2], prox[1]);
    EXPECT_GT(prox[1], prox[0]);
    for (int other : { 4, 5, 6, 7 })
        EXPECT_LT(prox[other], 30) << "sensor " << other;
}

TEST(ArenaSensing, ObstacleAheadIsSeenBySensorsAndCamera)
{
    // A blue cylinder 1 cm in front of the robot, on the dark floor.
    Arena arena = empty_arena();
    Obstacle cylinder;
    cylinder.shape = Obstacle::Shape::cylinder;
    cylinder.radius = 5;
    cylinder.x = arena_side / 2 + body_radius + 1 + cylinder.radius;
    cylinder.y = arena_side / 2;
    cylinder.color = { 0, 0, 1 };
    arena.obstacles = { cylinder };
    ArenaSimulation simulation(arena, 1, {});
    simulation.run_for(0.5);
    const epuck_named_variables &named = variables(simulation);
    // Uncalibrated still (the offsets come after 100 sets), so raw reflections.
    EXPECT_GT(named.prox[0], 500);
    EXPECT_GT(named.prox[7], 500);
    // The middle line looks 3.8 cm ahead of the lens, beyond the cylinder's
    // face: the camera shows the cylinder, not the floor behind it.
    EXPECT_EQ(named.cam_line[0], 50);
    EXPECT_GT(mean(named.cam_blue, 60), 80);
    EXPECT_LT(mean(named.cam_red, 60), 10);
}

TEST(ArenaSensing, IrValuesFallBackOnceTheObstacleIsGone)
{
    // Debian's Enki keeps the last value of a ray that meets nothing; a
    // robot 45 cm from a wall read 1213 there.
    ArenaSimulation simulation(empty_arena(), 1, {});
    simulation.run_for(calibration_seconds);
    simulation.world().place(0, facing_wall(1));
    simulation.run_for(0.1);
    ASSERT_GT(variables(simulation).prox[0], 500);
    simulation.world().place(0, { arena_side / 2, arena_side / 2, 0 });
    simulation.run_for(0.1);
    EXPECT_LT(simulation.world().robot(0).infrared[0].getValue(), 50);
    EXPECT_LT(variables(simulation).prox[0], 30);
    EXPECT_LT(variables(simulation).prox[7], 30);
}

TEST(ArenaSensing, RobotCarriesNoHiddenTurret)
{
    // Enki's EPuck(BASIC) steps its 8 IR sensors, a camera and a scanner
    // turret; ours, the 8 IR sensors, and Enki's camera only when rows of
    // the window look above the horizon (a tilt below 21°).
    ArenaSimulation tilted(empty_arena(), 1, {});
    EXPECT_EQ(tilted.world().robot(0).sensor_count(), 8u);
    Arena level_arena = empty_arena();
    level_arena.camera_tilt_degrees = 0;
    ArenaSimulation level(level_arena, 1, {});
    EXPECT_EQ(level.world().robot(0).sensor_count(), 9u);
}

TEST(ArenaSensing, LevelCameraSeesTheWallAhead)
{
    // No tilt: the line at 25 % looks above the horizon, through Enki's
    // camera, at the green wall 46 cm ahead.
    Arena arena = empty_arena();
    arena.camera_tilt_degrees = 0;
    arena.wall_color = { 0, 1, 0 };
    ArenaSimulation simulation(arena, 1, {});
    variables(simulation).cam_line[0] = 25;
    simulation.run_for(0.5);
    EXPECT_EQ(mean(variables(simulation).cam_green, 60), 94);
    EXPECT_EQ(mean(variables(simulation).cam_red, 60), 0);
}

TEST(ArenaSensing, RedFloorGivesRedCameraMeans)
{
    ArenaSimulation simulation(empty_arena({ 1, 0, 0 }), 1, {});
    simulation.run_for(0.5);
    const epuck_named_variables &named = variables(simulation);
    // Full red is 31 in RGB565's red field, times 3 in camR (hardware §3.5).
    EXPECT_EQ(mean(named.cam_red, 60), 93);
    EXPECT_EQ(mean(named.cam_green, 60), 0);
    EXPECT_EQ(mean(named.cam_blue, 60), 0);
}

TEST(ArenaSensing, CameraSeesTheAreaAheadNotTheOneBehind)
{
    // A blue band across the arena 3 to 13 cm ahead of the lens; the robot
    // stands on the dark floor. With the default 30° tilt, the annex's line
    // looks 5.3 cm ahead (docs/arena-format.md).
    Arena arena = empty_arena();
    GroundArea band;
    band.x = arena_side / 2 + body_radius + 3;
    band.y = 0;
    band.width = 10;
    band.height = arena_side;
    band.color = { 0, 0, 1 };
    arena.areas = { band };
    ArenaSimulation simulation(arena, 1, {});
    simulation.run_for(0.5);
    // The annex's line (32 % of the image) looks into the band.
    variables(simulation).cam_line[0] = 32;
    simulation.run_for(0.2);
    EXPECT_EQ(mean(variables(simulation).cam_blue, 60), 93);
    // Turned around, the band is behind: dark floor (0.2 → 6 of 31, x 3).
    simulation.world().place(0, { arena_side / 2, arena_side / 2, pi });
    simulation.run_for(0.2);
    EXPECT_EQ(mean(variables(simulation).cam_blue, 60), 18);
}

// The board reads a camera row at once (host_world's
// camera_every_second_pixel), the world working out the pixels read only:
// the same bytes as read one by one, for crowded robots, obstacles, rows
// past the window and pixels past the row, tilted or level.
TEST(ArenaSensing, CameraRowReadAtOnceIsTheRowReadByteByByte)
{
    for (double tilt : { 20.0, 0.0 }) {
        SCOPED_TRACE(tilt);
        Arena arena = default_arena(40);
        arena.camera_tilt_degrees = tilt;
        draw_start_positions(arena, 3);
        Obstacle box;
        box.shape = Obstacle::Shape::box;
        box.length = 30;
        box.width = 5;
        box.x = 100;
        box.y = 40;
        box.heading_degrees = 30;
        box.color = { 0, 0, 1 };
        arena.obstacles = { box };
        EnkiWorld world(arena, 1);
        world.step();
        std::map<uint8_t, unsigned> values;
        for (size_t robot = 0; robot < world.robot_count(); robot++) {
            const host_world &table = *world.world_of(robot);
            for (uint16_t row = 0; row < 122; row++) {
                constexpr uint16_t pixels = 64; // 4 past the row's 60
                uint8_t at_once[2 * pixels];
                table.camera_every_second_pixel(table.context, row, pixels, 0, at_once);
                for (uint16_t i = 0; i < 2 * pixels; i++) {
                    uint16_t index = uint16_t(4 * (i / 2) + i % 2);
                    ASSERT_EQ(at_once[i], table.camera_byte(table.context, row, index, 0))
                      << "robot " << robot << " row " << row << " byte " << i;
                    values[at_once[i]]++;
                }
            }
        }
        // Floors, areas, walls, robots and the box: many colours.
        EXPECT_GT(values.size(), 5u);
    }
}

// The board reads the selector's bits at once (host_world's inputs_read):
// the levels read one by one, at every position, and for other runs of
// inputs too.
TEST(ArenaSensing, InputsReadAtOnceAreTheInputsReadOneByOne)
{
    Arena arena = default_arena(2);
    EnkiWorld world(arena, 1);
    const host_world &table = *world.world_of(1);
    for (uint16_t position = 0; position < 16; position++) {
        world.set_selector(1, position);
        for (uint16_t first = EPUCK_PIN_FIRST_INPUT; first < EPUCK_PIN_COUNT; first++)
            for (uint16_t count = 1; first + count <= EPUCK_PIN_COUNT; count++) {
                uint16_t one_by_one = 0;
                for (uint16_t i = 0; i < count; i++)
                    if (table.pin_read(table.context, epuck_pin(first + i), 0))
                        one_by_one |= uint16_t(1u << i);
                ASSERT_EQ(table.inputs_read(table.context, epuck_pin(first), uint8_t(count), 0),
                          one_by_one)
                  << "position " << position << " pins " << first << " to " << first + count;
            }
    }
}

TEST(ArenaSensing, CollisionGivesAnAccelerometerShock)
{
    ArenaSimulation simulation(empty_arena(), 1, {});
    simulation.run_for(calibration_seconds);
    simulation.world().place(0, facing_wall(10));
    set_wheels(simulation, 1000, 1000);
    int16_t largest_before_contact = 0;
    int16_t largest_backward = 0;
    double deepest = 0;
    for (int step = 0; step < 150; step++) {
        simulation.step();
        const int16_t *acc = variables(simulation).acc;
        double gap = arena_side - body_radius - simulation.world().pose(0).x;
        if (gap > 1)
            largest_before_contact = std::max<int16_t>(
              largest_before_contact, int16_t(std::max(std::abs(acc[0]), std::abs(acc[1]))));
        largest_backward = std::max(largest_backward, acc[1]);
        deepest = std::max(deepest, simulation.world().robot(0).collision_depth);
    }
    EXPECT_LT(largest_before_contact, 50);
    // The annex calls above 1000 counts (1.3 g) a shock; a wall hit at
    // 12.8 cm/s stops and bounces the robot within one 10 ms step, several g
    // pointing backward (+Y).
    EXPECT_GT(largest_backward, 1000);
    // The depth is read before Enki clears it at the end of the step.
    EXPECT_GT(deepest, 0);
}

// Each axis's sign against the physics of a contact, from the e-puck's
// documented axes (hardware §3.3: +X right, +Y backward, Z up): a wall that
// stops the robot changes its velocity, and the accelerometer feels that
// change in the robot's frame. (The arena is flat: no tilt; the driver
// tests tilt the robot in a modelled world.)
namespace
{

struct Contact {
    const char *name;
    Pose start;
    int16_t left_speed, right_speed;
    int axis; // of acc
    int sign; // of the reading the contact gives
};

const Contact contacts[] = {
    // Stopped from the front: the change points backward, +Y.
    { "driving_into_a_wall_ahead", facing_wall(1), 1000, 1000, 1, +1 },
    // Stopped from behind: forward, -Y.
    { "backing_into_a_wall_behind",
      { arena_side - body_radius - 1, arena_side / 2, pi },
      -1000,
      -1000,
      1,
      -1 },
    // Facing +y, the wall at +x is on the robot's right: turning right
    // into it, it is pushed to its left, -X.
    { "turning_right_into_a_wall_on_its_right",
      { arena_side - body_radius - 2, arena_side / 2, pi / 2 },
      1000,
      300,
      0,
      -1 },
    // The mirror: turning left into a wall on its left pushes it right, +X.
    { "turning_left_into_a_wall_on_its_left",
      { body_radius + 2, arena_side / 2, pi / 2 },
      300,
      1000,
      0,
      +1 },
};

void PrintTo(const Contact &contact, std::ostream *out)
{
    *out << contact.name;
}

class AccelerometerAxes : public testing::TestWithParam<Contact>
{
};

} // namespace

TEST_P(AccelerometerAxes, FeelTheContactWithItsSign)
{
    const Contact &contact = GetParam();
    ArenaSimulation simulation(empty_arena(), 1, {});
    simulation.run_for(calibration_seconds);
    simulation.world().place(0, contact.start);
    set_wheels(simulation, contact.left_speed, contact.right_speed);
    int16_t lowest = 0, highest = 0;
    for (int step = 0; step < 150; step++) {
        simulation.step();
        int16_t reading = variables(simulation).acc[contact.axis];
        lowest = std::min(lowest, reading);
        highest = std::max(highest, reading);
        // Upright all along: 1 g up.
        EXPECT_NEAR(variables(simulation).acc[2], 768, 20) << "step " << step;
    }
    int16_t felt = contact.sign > 0 ? highest : lowest;
    int16_t opposite = contact.sign > 0 ? lowest : highest;
    // A contact at these speeds is some tenths of g at least (768 counts
    // per g); nothing of the other sign but noise.
    EXPECT_GT(contact.sign * felt, 300) << "lowest " << lowest << ", highest " << highest;
    EXPECT_GT(contact.sign * opposite, -50) << "lowest " << lowest << ", highest " << highest;
}

INSTANTIATE_TEST_SUITE_P(ArenaSensing,
                         AccelerometerAxes,
                         testing::ValuesIn(contacts),
                         [](const testing::TestParamInfo<Contact> &parameter) {
                             return std::string(parameter.param.name);
                         });

TEST(ArenaSensing, ShockAreaKnocksRobotsThatStay)
{
    // The whole floor is a shock area with a knock every 0.5 s.
    Arena arena = empty_arena();
    GroundArea area;
    area.width = arena_side;
    area.height = arena_side;
    area.color = { 1, 0.3, 0.3 };
    area.shock_period = 0.5;
    arena.areas = { area };
    ArenaSimulation simulation(arena, 1, {});
    simulation.run_for(calibration_seconds);
    int knocks = 0;
    bool was_knocked = false;
    for (int step = 0; step < 200; step++) {
        simulation.step();
        bool knocked = variables(simulation).acc[1] > 1000;
        knocks += knocked && !was_knocked;
        was_knocked = knocked;
    }
    // 2 s on the area: 4 knocks of 2 g (1536 counts), pointing backward.
    EXPECT_EQ(knocks, 4);
}

TEST(ArenaSensing, AnnexCallsAColourBadAfterAKnockOnIt)
{
    // The paper's controller on a red shock area: it must emit `bad 0`.
    Arena arena = empty_arena({ 1, 0.3, 0.3 });
    GroundArea area;
    area.width = arena_side;
    area.height = arena_side;
    area.color = { 1, 0.3, 0.3 };
    area.shock_period = 1;
    arena.areas = { area };
    ArenaSimulation simulation(arena, 1, compile("examples/paper-annex.aesl"));
    // A frame is length, source, type (protocol.md §2); user event 0 is `bad`.
    std::map<int, int> bad_by_colour;
    simulation.network().observe([&](aseba::host::FrameView frame) {
        auto word = [&](size_t at) { return int16_t(frame.bytes[at] | frame.bytes[at + 1] << 8); };
        if (frame.size >= 8 && word(4) == 0)
            bad_by_colour[word(6)]++;
    });
    simulation.run_for(4);
    EXPECT_GT(bad_by_colour[0], 0);
    EXPECT_EQ(bad_by_colour.size(), 1u);
}

class ArenaWheels : public testing::TestWithParam<int16_t>
{
};

TEST_P(ArenaWheels, StepsPerSecondMoveTheRobot)
{
    const int16_t speed = GetParam();
    ArenaSimulation simulation(empty_arena(), 1, {});
    simulation.world().place(0, { arena_side / 2, arena_side / 2, 0 });
    set_wheels(simulation, speed, speed);
    simulation.run_for(0.2);
    double start = simulation.world().pose(0).x;
    const double seconds = 2;
    simulation.run_for(seconds);
    double moved = simulation.world().pose(0).x - start;
    // 1000 steps a wheel turn, 12.8 cm a turn (hardware §3.6).
    double expected = speed * 12.8 / 1000 * seconds;
    EXPECT_NEAR(moved, expected, 0.05 * std::abs(expected));
    EXPECT_NEAR(simulation.world().pose(0).y, arena_side / 2, 1);
}

INSTANTIATE_TEST_SUITE_P(Speeds, ArenaWheels, testing::Values(1000, -1000, 500, 250));

TEST(ArenaWheels, OppositeSpeedsTurnOnTheSpot)
{
    ArenaSimulation simulation(empty_arena(), 1, {});
    set_wheels(simulation, -500, 500);
    simulation.run_for(1);
    Pose pose = simulation.world().pose(0);
    EXPECT_NEAR(pose.x, arena_side / 2, 0.5);
    EXPECT_NEAR(pose.y, arena_side / 2, 0.5);
    // Counter-clockwise (right wheel forward): the heading grows.
    EXPECT_GT(std::remainder(pose.heading, 2 * pi), 0.5);
}

TEST(ArenaNetwork, EmitsReachEveryOtherRobot)
{
    Arena arena = empty_arena();
    set_robot_count(arena, 3);
    ArenaSimulation simulation(arena, 1, compile("tests/arena/data/ping.aesl"));
    simulation.run_for(1);
    EXPECT_EQ(variables(simulation, 1).leds[0], 42);
    EXPECT_EQ(variables(simulation, 2).leds[0], 42);
}

namespace
{

// What a run ends with: each robot's pose, variables and battery charge.
struct RunResult {
    std::vector<Pose> poses;
    std::vector<std::vector<int16_t>> variables;
    std::vector<double> charges;
};

RunResult snapshot(ArenaSimulation &simulation)
{
    RunResult result;
    for (size_t i = 0; i < simulation.robot_count(); i++) {
        result.poses.push_back(simulation.world().pose(i));
        const auto &words = simulation.firmware(i).variables.words;
        result.variables.emplace_back(std::begin(words), std::end(words));
        result.charges.push_back(simulation.world().battery(i).charge());
    }
    return result;
}

// Checks that two runs ended alike, bit for bit; returns whether a third
// one, `other`, differs somewhere.
bool expect_same_run(const RunResult &first, const RunResult &second, const RunResult &other)
{
    bool differs = false;
    for (size_t i = 0; i < first.poses.size(); i++) {
        EXPECT_EQ(std::memcmp(&first.poses[i], &second.poses[i], sizeof(Pose)), 0) << "robot " << i;
        EXPECT_EQ(first.variables[i], second.variables[i]) << "robot " << i;
        EXPECT_EQ(first.charges[i], second.charges[i]) << "robot " << i;
        differs |= std::memcmp(&first.poses[i], &other.poses[i], sizeof(Pose)) != 0 ||
                   first.variables[i] != other.variables[i];
    }
    return differs;
}

RunResult run_annex(uint32_t seed, const std::vector<uint16_t> &bytecode, unsigned threads = 1)
{
    ArenaSimulation simulation(default_arena(), seed, bytecode, {}, threads);
    simulation.run_for(10);
    return snapshot(simulation);
}

} // namespace

TEST(ArenaDeterminism, SameSeedSameRunBitForBit)
{
    std::vector<uint16_t> annex = compile("examples/paper-annex.aesl");
    RunResult first = run_annex(7, annex);
    RunResult second = run_annex(7, annex);
    RunResult other_seed = run_annex(8, annex);
    EXPECT_TRUE(expect_same_run(first, second, other_seed)) << "the seed changed nothing";
    // The robots did move in these 10 s.
    for (size_t i = 0; i < first.poses.size(); i++)
        EXPECT_GT(std::hypot(first.poses[i].x - default_arena().robots[i].x,
                             first.poses[i].y - default_arena().robots[i].y),
                  5);
}

// The robots' firmware on several threads: the same run as on one.
TEST(ArenaDeterminism, SameRunWhateverTheThreadCount)
{
    std::vector<uint16_t> annex = compile("examples/paper-annex.aesl");
    RunResult one_thread = run_annex(7, annex, 1);
    RunResult three_threads = run_annex(7, annex, 3);
    RunResult other_seed = run_annex(8, annex, 3);
    EXPECT_TRUE(expect_same_run(one_thread, three_threads, other_seed))
      << "the seed changed nothing";
}

namespace
{

// The sound arena with starts drawn from the seed, selectors, a battery that
// runs low and remote key presses, running the sound-direction example.
RunResult run_every_input(uint32_t seed, const std::vector<uint16_t> &bytecode)
{
    Arena arena = read_arena_file("examples/sound.arena");
    arena.battery.capacity_mah = 1;
    for (size_t i = 0; i < arena.robots.size(); i++) {
        arena.robots[i].selector = uint16_t(3 * i);
        arena.robots[i].battery_charge = 0.06;
    }
    draw_start_positions(arena, seed);
    ArenaSimulation simulation(arena, seed, bytecode);
    simulation.run_for(1);
    simulation.press_remote_key({ 0, 2 }, 0, 12);
    simulation.set_selector(1, 7);
    simulation.run_for(1);
    return snapshot(simulation);
}

} // namespace

TEST(ArenaDeterminism, SameSeedSameRunWithSoundSelectorsRemoteAndBattery)
{
    std::vector<uint16_t> program = compile("examples/sound-direction.aesl");
    RunResult first = run_every_input(5, program);
    RunResult second = run_every_input(5, program);
    RunResult other_seed = run_every_input(6, program);
    EXPECT_TRUE(expect_same_run(first, second, other_seed)) << "the seed changed nothing";
    // The run did use the new inputs: recordings, a remote key, a selector
    // and a battery run low (1 mAh from 6 %: 0.01 mAh in 0.3 s or less).
    const epuck_named_variables &robot1 =
      *reinterpret_cast<const epuck_named_variables *>(first.variables[0].data());
    const epuck_named_variables &robot2 =
      *reinterpret_cast<const epuck_named_variables *>(first.variables[1].data());
    EXPECT_EQ(robot1.rc5[0], 12);
    EXPECT_EQ(robot2.selector[0], 7);
    EXPECT_EQ(robot1.battery[0], 0);
    EXPECT_NE(std::count(std::begin(robot1.mic_samples0), std::end(robot1.mic_samples0), 0), 32);
}

// The lit reading rounds as std::lround did: halves up, whatever the
// ambient reading and Enki's value (clamped to 0..ambient).
TEST(ArenaSensing, ProximityLitReadingRoundsAsLround)
{
    const uint16_t ambients[] = { 0, 1, 3731, 4095, 65535 };
    const double values[] = {
        -5,     0,    0.25, 0.5,  0.5000000000000001, 0.49999999999999994, 1.5, 2.5, 100.49, 100.5,
        3730.5, 3731, 5000, 1e300
    };
    for (uint16_t ambient : ambients)
        for (double value : values) {
            const double reflected = std::clamp(value, 0.0, double(ambient));
            EXPECT_EQ(proximity_lit_reading(value, ambient),
                      uint16_t(std::lround(double(ambient) - reflected)))
              << value << " under " << ambient;
        }
    for (int step = 0; step <= 8000; step++) {
        const double value = step * 0.5 + (step % 3) * 1e-9;
        EXPECT_EQ(proximity_lit_reading(value, 4095),
                  uint16_t(std::lround(4095.0 - std::clamp(value, 0.0, 4095.0))))
          << value;
    }
}
