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
    ASSERT_EQ(arena.robots.size(), 2u);
    EXPECT_EQ(arena.robots[0].node_id, 3);
    EXPECT_EQ(arena.robots[1].heading_degrees, -45);
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
                  BadArena{ "size 100 100\narea disc 1 2 3 0 0 0 shock 0\n", "above 0" }));

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
