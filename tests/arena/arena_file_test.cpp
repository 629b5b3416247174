// Arena files (docs/arena-format.md): what a file says is what the arena
// holds, mistakes are reported with their line, and robots can be added.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tools/emulator/arena_file.hpp"

using namespace aseba::arena;

TEST(ArenaFile, ReadsEveryStatement)
{
    Arena arena = read_arena_file("tests/arena/data/every-statement.arena");
    EXPECT_EQ(arena.width, 120);
    EXPECT_EQ(arena.height, 80);
    EXPECT_EQ(arena.wall_color.red, 0.5);
    EXPECT_EQ(arena.floor_color.blue, 0.3);
    EXPECT_EQ(arena.camera_tilt_degrees, 25);
    EXPECT_EQ(arena.wheel_noise, 0);
    ASSERT_EQ(arena.areas.size(), 2u);
    EXPECT_EQ(arena.areas[0].shape, GroundArea::Shape::rectangle);
    EXPECT_EQ(arena.areas[0].width, 30);
    EXPECT_EQ(arena.areas[0].shock_period, 0.5);
    EXPECT_EQ(arena.areas[1].shock_period, 0);
    EXPECT_EQ(arena.areas[1].shape, GroundArea::Shape::disc);
    EXPECT_EQ(arena.areas[1].radius, 12);
    ASSERT_EQ(arena.obstacles.size(), 2u);
    EXPECT_EQ(arena.obstacles[0].shape, Obstacle::Shape::box);
    EXPECT_EQ(arena.obstacles[0].heading_degrees, 30);
    EXPECT_EQ(arena.obstacles[1].shape, Obstacle::Shape::cylinder);
    EXPECT_EQ(arena.obstacles[1].color.blue, 1);
    ASSERT_EQ(arena.sounds.size(), 2u);
    EXPECT_EQ(arena.sounds[0].x, 60);
    EXPECT_EQ(arena.sounds[0].frequency, 1000);
    EXPECT_EQ(arena.sounds[0].level, 500);
    EXPECT_EQ(arena.sounds[0].start, 0);
    EXPECT_EQ(arena.sounds[0].stop, SoundSource::never);
    EXPECT_EQ(arena.sounds[1].frequency, 440);
    EXPECT_EQ(arena.sounds[1].start, 2);
    EXPECT_EQ(arena.sounds[1].stop, 30);
    EXPECT_EQ(arena.sounds[1].beep_on, 0.5);
    EXPECT_EQ(arena.sounds[1].beep_off, 1.5);
    EXPECT_EQ(arena.battery.capacity_mah, 1200);
    EXPECT_EQ(arena.battery.idle_ma, 100);
    EXPECT_EQ(arena.battery.motor_ma, 160);
    ASSERT_EQ(arena.robots.size(), 3u);
    EXPECT_EQ(arena.robots[0].node_id, 3);
    EXPECT_EQ(arena.robots[0].selector, 0);
    EXPECT_EQ(arena.robots[0].battery_charge, 1);
    EXPECT_EQ(arena.robots[1].heading_degrees, -45);
    EXPECT_EQ(arena.robots[1].selector, 12);
    EXPECT_EQ(arena.robots[1].battery_charge, 0.4);
    EXPECT_EQ(arena.robots[2].node_id, RobotPlacement::node_id_from_selector);
    EXPECT_EQ(arena.robots[2].selector, 3);
    EXPECT_EQ(arena.robots[2].battery_charge, 0.05);
}

TEST(ArenaFile, SoundsFollowTheirSchedule)
{
    Arena arena = read_arena_file("tests/arena/data/every-statement.arena");
    const SoundSource &always = arena.sounds[0], &beeper = arena.sounds[1];
    EXPECT_TRUE(always.sounding(0));
    EXPECT_TRUE(always.sounding(1e6));
    // On from 2 s for 0.5 s every 2 s, until 30 s.
    EXPECT_FALSE(beeper.sounding(1.99));
    EXPECT_TRUE(beeper.sounding(2));
    EXPECT_TRUE(beeper.sounding(2.49));
    EXPECT_FALSE(beeper.sounding(2.51));
    EXPECT_FALSE(beeper.sounding(3.99));
    EXPECT_TRUE(beeper.sounding(4.2));
    EXPECT_TRUE(beeper.sounding(28.1));
    EXPECT_FALSE(beeper.sounding(30.1));
}

TEST(ArenaFile, GroundColourIsTheLastAreaContainingThePoint)
{
    Arena arena = read_arena_file("tests/arena/data/every-statement.arena");
    // Inside the rectangle only, inside both (the disc comes later), outside.
    EXPECT_EQ(arena.ground_color(15, 25).red, 1);
    EXPECT_EQ(arena.ground_color(38, 30).green, 1); // 7 cm from the disc's centre
    EXPECT_EQ(arena.ground_color(5, 5).blue, 0.3);
}

struct BadArena {
    const char *text;
    const char *message;
};

class ArenaFileErrors : public testing::TestWithParam<BadArena>
{
};

TEST_P(ArenaFileErrors, NameTheLineAndTheMistake)
{
    try {
        parse_arena(GetParam().text, "bad.arena");
        FAIL() << "accepted: " << GetParam().text;
    } catch (const std::runtime_error &error) {
        EXPECT_NE(std::string(error.what()).find(GetParam().message), std::string::npos)
          << error.what();
    }
}

INSTANTIATE_TEST_SUITE_P(
  Mistakes,
  ArenaFileErrors,
  testing::Values(BadArena{ "robot 1 10 10 0\n", "no 'size'" },
                  BadArena{ "size 100\n", "bad.arena:1: missing value" },
                  BadArena{ "size 100 100\nfloor 2 0 0\n", "bad.arena:2: colour" },
                  BadArena{ "size 100 100\narea triangle 1 2 3 0 0 0\n", "triangle" },
                  BadArena{ "size 100 100\nrobot 1 10 10 0\nrobot 1 20 20 0\n", "used twice" },
                  BadArena{ "size 100 100\nrobot 1 150 10 0\n", "outside" },
                  BadArena{ "size 100 100 7\n", "unexpected '7'" },
                  BadArena{ "size 100 100\nteleport 1\n", "unknown statement" },
                  BadArena{ "size 100 100\narea disc 1 2 3 0 0 0 zap 1\n", "'shock SECONDS'" },
                  BadArena{ "size 100 100\narea disc 1 2 3 0 0 0 shock 0\n", "above 0" },
                  BadArena{ "size 100 100\nrobot 0 10 10 0\n", "or '-'" },
                  BadArena{ "size 100 100\nrobot 1 10 10 0 selector 16\n", "0 to 15" },
                  BadArena{ "size 100 100\nrobot 1 10 10 0 selector 2.5\n", "0 to 15" },
                  BadArena{ "size 100 100\nrobot 1 10 10 0 battery 0\n", "above 0 to 100" },
                  BadArena{ "size 100 100\nrobot 1 10 10 0 battery 101\n", "above 0 to 100" },
                  BadArena{ "size 100 100\nrobot 1 10 10 0 speed 3\n", "'selector N'" },
                  BadArena{ "size 100 100\nrobot 1 10 10 0 selector 1 selector 2\n",
                            "'selector' is given twice" },
                  BadArena{ "size 100 100\nrobot - 10 10 0\nrobot - 150 10 0\n",
                            "robot number 2 (id '-') stands outside" },
                  BadArena{ "size 100 100\nsound 10 10 9000 100\n", "up to 8192 Hz" },
                  BadArena{ "size 100 100\nsound 10 10 1000 0\n", "level must be above 0" },
                  BadArena{ "size 100 100\nsound 10 10 1000 5 start 3 stop 2\n",
                            "stops after it starts" },
                  BadArena{ "size 100 100\nsound 10 10 1000 5 beep 1\n", "missing value" },
                  BadArena{ "size 100 100\nsound 10 10 1000 5 loud\n", "'beep ON OFF'" },
                  BadArena{ "size 100 100\nsound 200 10 1000 5\n", "sound 1 stands outside" },
                  BadArena{ "size 100 100\nbattery 0\n", "capacity must be above 0" },
                  BadArena{ "size 100 100\nbattery 100 20\n", "missing value" },
                  BadArena{ "size 100 100\nbattery 100 -1 2\n", "not be below 0" }));

TEST(ArenaFile, RobotsWithoutAnIdMayShareTheirSelectorsId)
{
    Arena arena = parse_arena("size 100 100\nrobot - 10 10 0\nrobot - 20 20 0\n", "ok.arena");
    EXPECT_EQ(arena.robots.size(), 2u);
}

TEST(ArenaFile, AddedRobotsAreClearOfWallsObstaclesAndEachOther)
{
    Arena arena = read_arena_file("tests/arena/data/every-statement.arena");
    set_robot_count(arena, 30);
    ASSERT_EQ(arena.robots.size(), 30u);
    const double body = 3.7;
    for (size_t i = 0; i < arena.robots.size(); i++) {
        const RobotPlacement &a = arena.robots[i];
        EXPECT_GE(a.x, body);
        EXPECT_LE(a.x, arena.width - body);
        for (size_t j = i + 1; j < arena.robots.size(); j++) {
            EXPECT_NE(a.node_id, arena.robots[j].node_id);
            EXPECT_GE(std::hypot(a.x - arena.robots[j].x, a.y - arena.robots[j].y), 2 * body);
        }
    }
    set_robot_count(arena, 1);
    EXPECT_EQ(arena.robots.size(), 1u);
    EXPECT_EQ(arena.robots[0].node_id, 3);
    EXPECT_THROW(set_robot_count(arena, 10000), std::runtime_error);
}

// Drawn starts: inside, clear of the walls (a body and 1 cm), of each other,
// and of every coloured area; the same seed gives the same places.
TEST(ArenaFile, DrawnStartsAreFreeAndFollowTheSeed)
{
    const double body = 3.7, clearance = 1;
    Arena original = default_arena();
    Arena first = original, again = original, other = original;
    draw_start_positions(first, 1);
    draw_start_positions(again, 1);
    draw_start_positions(other, 2);
    ASSERT_EQ(first.robots.size(), original.robots.size());
    bool seed_matters = false;
    for (size_t i = 0; i < first.robots.size(); i++) {
        const RobotPlacement &robot = first.robots[i];
        EXPECT_EQ(robot.node_id, original.robots[i].node_id);
        EXPECT_GE(robot.x, body + clearance);
        EXPECT_LE(robot.x, first.width - body - clearance);
        EXPECT_GE(robot.y, body + clearance);
        EXPECT_LE(robot.y, first.height - body - clearance);
        EXPECT_GE(robot.heading_degrees, 0);
        EXPECT_LT(robot.heading_degrees, 360);
        for (const GroundArea &area : first.areas) // the default arena's discs
            EXPECT_GT(std::hypot(robot.x - area.x, robot.y - area.y), area.radius + body);
        for (size_t j = i + 1; j < first.robots.size(); j++)
            EXPECT_GE(std::hypot(robot.x - first.robots[j].x, robot.y - first.robots[j].y),
                      2 * (body + clearance));
        EXPECT_EQ(robot.x, again.robots[i].x);
        EXPECT_EQ(robot.heading_degrees, again.robots[i].heading_degrees);
        seed_matters |= robot.x != other.robots[i].x;
    }
    EXPECT_TRUE(seed_matters);
    // Rectangles too, and obstacles; and a robot that cannot fit is an error.
    Arena every = read_arena_file("tests/arena/data/every-statement.arena");
    draw_start_positions(every, 3);
    for (const RobotPlacement &robot : every.robots)
        EXPECT_EQ(every.ground_color(robot.x, robot.y).blue, 0.3) << robot.x << ", " << robot.y;
    Arena covered =
      parse_arena("size 50 50\narea rectangle 0 0 50 50 1 0 0\nrobot 1 25 25 0\n", "covered.arena");
    EXPECT_THROW(draw_start_positions(covered, 1), std::runtime_error);
}

TEST(ArenaFile, DefaultArenaIsThePapersSetup)
{
    Arena arena = default_arena();
    EXPECT_EQ(arena.width, arena.height);
    EXPECT_EQ(arena.robots.size(), 6u);
    ASSERT_EQ(arena.areas.size(), 3u);
    // Red, green and blue, in the annex's colour numbering (0, 1, 2).
    EXPECT_GT(arena.areas[0].color.red, arena.areas[0].color.green);
    EXPECT_GT(arena.areas[1].color.green, arena.areas[1].color.blue);
    EXPECT_GT(arena.areas[2].color.blue, arena.areas[2].color.red);
    // A thousand robots get a larger square.
    Arena large = default_arena(1000);
    EXPECT_EQ(large.robots.size(), 1000u);
    EXPECT_GT(large.width, arena.width);
}
