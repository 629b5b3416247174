// The arena's grid-stepped Enki world against Enki's own step: the same
// robots, obstacles and wheel commands give the same run, bit for bit, in a
// crowd where robots keep bumping into each other, the obstacles and the
// walls; also with its sensing pass shared out over threads.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

#include "tools/emulator/enki_world.hpp"
#include "tools/emulator/partitioned_world.hpp"
#include "tools/emulator/worker_pool.hpp"

using aseba::arena::EnkiEpuck;
using aseba::arena::PartitionedWorld;
using aseba::arena::WorkerPool;

namespace
{

constexpr double side = 120; // cm
constexpr size_t robot_count = 64;
constexpr double spacing = 8; // cm between robot centres: a 0.6 cm gap
constexpr double step_seconds = 0.01;
constexpr int steps = 600;

struct RobotRecord {
    double x, y, angle;
    double infrared[EnkiEpuck::ir_count];
    double camera; // a sum over the camera's pixels, when it is stepped
};

struct CrowdRun {
    std::vector<RobotRecord> robots;
    unsigned collisions = 0;
};

// Runs the crowd in `world` (fresh, square, side x side); robots and
// obstacles live in one block each, in order, as the arena keeps them.
// With `camera`, Enki steps the robots' cameras too; `cylinder_radius` wider
// than a cell puts the cylinder outside the grid.
CrowdRun run_crowd(Enki::World &world, bool camera = false, double cylinder_radius = 6)
{
    world.takeObjectOwnership = false;
    world.setRandomSeed(11);
    aseba::arena::seed_ir_noise(11);
    std::allocator<EnkiEpuck> robot_allocator;
    EnkiEpuck *robots = robot_allocator.allocate(robot_count);
    std::allocator<Enki::PhysicalObject> obstacle_allocator;
    Enki::PhysicalObject *obstacles = obstacle_allocator.allocate(2);
    const size_t columns = 8;
    for (size_t i = 0; i < robot_count; i++) {
        EnkiEpuck *robot = new (robots + i) EnkiEpuck(0.05, 0.5, camera);
        robot->pos =
          Enki::Point(30 + spacing * double(i % columns), 30 + spacing * double(i / columns));
        robot->angle = double(i * 37 % 360) * M_PI / 180;
        world.addObject(robot);
    }
    new (obstacles) Enki::PhysicalObject;
    obstacles[0].setRectangular(20, 4, 10, -1);
    obstacles[0].pos = Enki::Point(60, 100);
    obstacles[0].angle = 0.3;
    world.addObject(&obstacles[0]);
    new (obstacles + 1) Enki::PhysicalObject;
    obstacles[1].setCylindric(cylinder_radius, 10, -1);
    obstacles[1].pos = Enki::Point(100, 50);
    world.addObject(&obstacles[1]);

    CrowdRun run;
    for (int step = 0; step < steps; step++) {
        for (size_t i = 0; i < robot_count; i++) {
            // Wheel commands that change now and then: robots push, turn
            // and scatter.
            int phase = (step / 100 + int(i)) % 4;
            robots[i].leftSpeed = phase == 0 ? 12 : phase == 1 ? -6 : 10;
            robots[i].rightSpeed = phase == 0 ? 12 : phase == 1 ? 8 : -4;
        }
        world.step(step_seconds);
        for (size_t i = 0; i < robot_count; i++)
            run.collisions += robots[i].collisions;
    }
    for (size_t i = 0; i < robot_count; i++) {
        RobotRecord record{ robots[i].pos.x, robots[i].pos.y, robots[i].angle, {}, 0 };
        for (unsigned sensor = 0; sensor < EnkiEpuck::ir_count; sensor++)
            record.infrared[sensor] = robots[i].infrared[sensor].getValue();
        for (size_t pixel = 0; pixel < robots[i].camera.image.size(); pixel++) {
            const Enki::Color &color = robots[i].camera.image[pixel];
            record.camera += double(pixel + 1) * (color.r() + 2 * color.g() + 3 * color.b());
        }
        run.robots.push_back(record);
    }
    world.objects.clear();
    for (size_t i = 0; i < robot_count; i++)
        robots[i].~EnkiEpuck();
    obstacles[0].~PhysicalObject();
    obstacles[1].~PhysicalObject();
    robot_allocator.deallocate(robots, robot_count);
    obstacle_allocator.deallocate(obstacles, 2);
    return run;
}

} // namespace

TEST(PartitionedWorld, StepsAsEnkiDoesBitForBit)
{
    Enki::World enki(side, side, Enki::Color::gray);
    CrowdRun expected = run_crowd(enki);
    PartitionedWorld partitioned(side, side, Enki::Color::gray);
    CrowdRun got = run_crowd(partitioned);

    // The crowd did collide, often.
    EXPECT_GT(expected.collisions, 1000u);
    EXPECT_EQ(got.collisions, expected.collisions);
    ASSERT_EQ(got.robots.size(), expected.robots.size());
    for (size_t i = 0; i < got.robots.size(); i++)
        EXPECT_EQ(std::memcmp(&got.robots[i], &expected.robots[i], sizeof(RobotRecord)), 0)
          << "robot " << i << " at " << got.robots[i].x << ", " << got.robots[i].y << ", Enki's at "
          << expected.robots[i].x << ", " << expected.robots[i].y;
    EXPECT_EQ(partitioned.margin_overruns(), 0u);
}

TEST(PartitionedWorld, StepsAsEnkiDoesWithAnObstacleWiderThanACell)
{
    Enki::World enki(side, side, Enki::Color::gray);
    CrowdRun expected = run_crowd(enki, false, 30);
    PartitionedWorld partitioned(side, side, Enki::Color::gray);
    CrowdRun got = run_crowd(partitioned, false, 30);

    EXPECT_EQ(got.collisions, expected.collisions);
    ASSERT_EQ(got.robots.size(), expected.robots.size());
    for (size_t i = 0; i < got.robots.size(); i++)
        EXPECT_EQ(std::memcmp(&got.robots[i], &expected.robots[i], sizeof(RobotRecord)), 0)
          << "robot " << i;
}

namespace
{

// Compares two crowd runs bit for bit.
void expect_same_crowd(const CrowdRun &got, const CrowdRun &expected)
{
    EXPECT_EQ(got.collisions, expected.collisions);
    ASSERT_EQ(got.robots.size(), expected.robots.size());
    for (size_t i = 0; i < got.robots.size(); i++)
        EXPECT_EQ(std::memcmp(&got.robots[i], &expected.robots[i], sizeof(RobotRecord)), 0)
          << "robot " << i;
}

} // namespace

// The sensing pass on three threads, with and without the cameras: the
// same run as Enki's own step.
TEST(PartitionedWorld, StepsAsEnkiDoesOnSeveralThreads)
{
    for (bool camera : { false, true }) {
        SCOPED_TRACE(camera ? "with cameras" : "without cameras");
        Enki::World enki(side, side, Enki::Color::gray);
        CrowdRun expected = run_crowd(enki, camera);
        WorkerPool workers(3);
        PartitionedWorld partitioned(side, side, Enki::Color::gray);
        partitioned.set_parallel_for(
          [&workers](size_t count, const std::function<void(size_t, size_t)> &work) {
              workers.run(count, work);
          });
        CrowdRun got = run_crowd(partitioned, camera);
        expect_same_crowd(got, expected);
        double pixels = 0;
        for (const RobotRecord &robot : got.robots)
            pixels += robot.camera;
        EXPECT_EQ(pixels > 0, camera) << "the cameras saw something only when stepped";
    }
}
