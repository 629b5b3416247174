// The arena's IR sensor against Enki's own: the same ray distances and
// values, bit for bit, for robots, cylinders and boxes all around the
// sensor, also where a ray's line just touches or just misses an object
// (where the sensor skips Enki's test for rays that cannot reach).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "tools/emulator/enki_world.hpp"

using aseba::arena::EnkiEpuck;
using aseba::arena::FreshIRSensor;

namespace
{

constexpr double pi = 3.14159265358979323846;
constexpr double step_seconds = 0.01;

// Enki's sensor as Debian's library has it, with its rays cleared at the
// start of every step as FreshIRSensor's are.
class EnkiIRSensor : public Enki::IRSensor
{
  public:
    using Enki::IRSensor::IRSensor;
    void init(double dt, Enki::World *world) override
    {
        Enki::IRSensor::init(dt, world);
        std::fill(rayValues.begin(), rayValues.end(), 0.0);
    }
};

// The e-puck's front-right sensor (enki_world.cpp), on the robot's rim.
const Enki::Vector sensor_position(3.35, -1.05);
constexpr double sensor_heading = -18 * pi / 180;
constexpr double sensor_height = 2.5;
constexpr double sensor_range = 12;

template<typename Sensor>
Sensor make_sensor(Enki::Robot *owner)
{
    return Sensor(
      owner, sensor_position, sensor_height, sensor_heading, sensor_range, 3731, 0.3, 0.7, 10);
}

bool same_bits(double a, double b)
{
    return std::memcmp(&a, &b, sizeof a) == 0;
}

struct Comparison {
    unsigned rays_seeing = 0; // rays whose distance is below the range
    unsigned differences = 0;
};

// Steps both sensors with `objects` and compares their rays.
void compare(Enki::World &world,
             FreshIRSensor &fresh,
             EnkiIRSensor &enki,
             const std::vector<Enki::PhysicalObject *> &objects,
             Comparison &comparison)
{
    fresh.init(step_seconds, &world);
    enki.init(step_seconds, &world);
    for (Enki::PhysicalObject *object : objects) {
        fresh.objectStep(step_seconds, &world, object);
        enki.objectStep(step_seconds, &world, object);
    }
    for (unsigned ray = 0; ray < enki.getRayCount(); ray++) {
        if (enki.getRayDist(ray) < sensor_range)
            comparison.rays_seeing++;
        if (!same_bits(fresh.getRayDist(ray), enki.getRayDist(ray)) ||
            !same_bits(fresh.getRayValue(ray), enki.getRayValue(ray))) {
            comparison.differences++;
            ADD_FAILURE() << "ray " << ray << ": " << fresh.getRayDist(ray) << " "
                          << fresh.getRayValue(ray) << ", Enki's " << enki.getRayDist(ray) << " "
                          << enki.getRayValue(ray);
        }
    }
    // The sensor's place for the step is Enki's too.
    EXPECT_TRUE(same_bits(fresh.getAbsolutePosition().x, enki.getAbsolutePosition().x));
    EXPECT_TRUE(same_bits(fresh.getAbsolutePosition().y, enki.getAbsolutePosition().y));
    EXPECT_TRUE(same_bits(fresh.getAbsoluteOrientation(), enki.getAbsoluteOrientation()));
    EXPECT_TRUE(same_bits(fresh.getAbsSmartPos().x, enki.getAbsSmartPos().x));
    EXPECT_TRUE(same_bits(fresh.getAbsSmartPos().y, enki.getAbsSmartPos().y));
}

} // namespace

// Cylinders (robots, posts, one too low to be seen) anywhere around the
// sensor, and placed so that a ray's line passes at their radius, a hair
// inside or a hair outside.
TEST(IrSensor, SeesCylindersAsEnkiDoesBitForBit)
{
    Enki::World world(200, 200);
    world.takeObjectOwnership = false;
    EnkiEpuck robot(0, 0.5, false);
    FreshIRSensor fresh = make_sensor<FreshIRSensor>(&robot);
    EnkiIRSensor enki = make_sensor<EnkiIRSensor>(&robot);
    struct Shape {
        double radius, height;
    };
    const Shape shapes[] = { { 3.7, 4.7 }, { 6, 10 }, { 0.5, 10 }, { 3.7, 1 } };
    std::vector<Enki::PhysicalObject> objects(std::size(shapes));
    for (size_t i = 0; i < objects.size(); i++)
        objects[i].setCylindric(shapes[i].radius, shapes[i].height, 100);

    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> unit(0, 1);
    const double ray_offsets[] = { -15 * pi / 180, 0, 15 * pi / 180 };
    const double hairs[] = { -1e-6, -1e-9, -1e-12, 0, 1e-12, 1e-9, 1e-6 };
    Comparison comparison;
    unsigned trials = 0;
    for (int trial = 0; trial < 4000; trial++) {
        robot.pos = Enki::Point(20 + 160 * unit(random), 20 + 160 * unit(random));
        robot.angle = -pi + 2 * pi * unit(random);
        const Enki::Matrix22 rotation(robot.angle);
        const Enki::Point sensor = robot.pos + rotation * sensor_position;
        for (size_t shape = 0; shape < objects.size(); shape++) {
            Enki::PhysicalObject &object = objects[shape];
            double radius = shapes[shape].radius;
            // Anywhere within reach, in front or behind.
            double bearing = 2 * pi * unit(random);
            double distance = (sensor_range + radius + 2) * unit(random);
            object.pos = sensor + Enki::Vector(std::cos(bearing), std::sin(bearing)) * distance;
            compare(world, fresh, enki, { &object }, comparison);
            trials++;
            // A ray's line at the object's radius, give or take a hair.
            double ray = robot.angle + sensor_heading + ray_offsets[trial % 3];
            Enki::Vector along(std::cos(ray), std::sin(ray));
            double reach = (sensor_range + radius) * unit(random);
            double hair = hairs[(trial / 3) % std::size(hairs)];
            object.pos = sensor + along * reach + along.perp() * (radius * (1 + hair));
            compare(world, fresh, enki, { &object }, comparison);
            trials++;
        }
    }
    EXPECT_EQ(comparison.differences, 0u);
    // Enough rays saw something for the comparison to mean something.
    EXPECT_GT(comparison.rays_seeing, trials / 2);
}

// Boxes (the arena's obstacles) around the sensor, and several objects
// seen in one step: the nearest wins, as in Enki.
TEST(IrSensor, SeesBoxesAndCrowdsAsEnkiDoesBitForBit)
{
    Enki::World world(200, 200);
    world.takeObjectOwnership = false;
    std::vector<Enki::PhysicalObject> boxes(3);
    const double box_places[][3] = { { 50, 50, 0.3 }, { 100, 120, 1.2 }, { 150, 60, -2 } };
    for (size_t i = 0; i < boxes.size(); i++) {
        boxes[i].pos = Enki::Point(box_places[i][0], box_places[i][1]);
        boxes[i].angle = box_places[i][2];
        boxes[i].setRectangular(20, 4, 10, -1);
        world.addObject(&boxes[i]);
    }
    // Enki places a box's polygon in the world during a step.
    world.step(step_seconds);
    std::vector<Enki::PhysicalObject> robots(6);
    for (Enki::PhysicalObject &other : robots)
        other.setCylindric(3.7, 4.7, 152);

    EnkiEpuck robot(0, 0.5, false);
    FreshIRSensor fresh = make_sensor<FreshIRSensor>(&robot);
    EnkiIRSensor enki = make_sensor<EnkiIRSensor>(&robot);
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> unit(0, 1);
    Comparison comparison;
    unsigned trials = 0;
    for (int trial = 0; trial < 3000; trial++) {
        const Enki::PhysicalObject &box = boxes[size_t(trial) % boxes.size()];
        double bearing = 2 * pi * unit(random);
        double distance = 25 * unit(random);
        robot.pos = box.pos + Enki::Vector(std::cos(bearing), std::sin(bearing)) * distance;
        robot.angle = -pi + 2 * pi * unit(random);
        std::vector<Enki::PhysicalObject *> seen;
        for (Enki::PhysicalObject &other : robots) {
            double around = 2 * pi * unit(random);
            other.pos = robot.pos +
                        Enki::Vector(std::cos(around), std::sin(around)) * (8 + 12 * unit(random));
            seen.push_back(&other);
        }
        for (Enki::PhysicalObject &other : boxes)
            seen.push_back(&other);
        compare(world, fresh, enki, seen, comparison);
        trials++;
    }
    EXPECT_EQ(comparison.differences, 0u);
    EXPECT_GT(comparison.rays_seeing, trials / 2);
    world.objects.clear();
}
