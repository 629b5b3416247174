// The arena's IR sensor against Enki's own and against the geometry worked
// out independently: boxes give Enki's ray distances and values bit for
// bit (Enki's test, for the rays that may reach); cylinders (robots, posts)
// give the distances where each ray's line meets the circle, as Enki's do,
// up to rounding (the sensor uses no trigonometry there, Enki an arc
// tangent and a sine), also where a ray's line just touches or just misses
// an object.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
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

// How far rays and values may stray from each other up to rounding: the
// distances agree within about 1e-13 cm away from a tangent (the cross
// product's rounding against the sine's), the values within their slope
// (at most about 1e4 per cm) times that.
constexpr double distance_tolerance = 1e-7;
constexpr double value_tolerance = 1e-2;

// Enki's response function m (c - x0^2) / (x^2 - 2 x0 x + c) of the
// e-puck's sensor (enki_world.cpp), in long double.
long double response(long double x)
{
    const long double m = 3731, x0 = 0.3L, c = 0.7L;
    if (x < x0)
        return m;
    if (x > sensor_range)
        return 0;
    return m * (c - x0 * x0) / (x * x - 2 * x0 * x + c);
}

struct Comparison {
    unsigned rays_seeing = 0; // rays whose distance is below the range
    unsigned differences = 0;
    unsigned tangents = 0; // rays whose line touches a circle within rounding
};

// Where each of the sensor's rays meets the cylinders `objects` (their
// bounding circles), worked out in long double from the sensor's place for
// the step, as Enki's sensor is described: an object counts when its
// circle meets the circle around the rays (centred half the range along
// the sensor's heading, of radius range * sqrt(1.25 - cos 15°)); a ray is
// then the line through the sensor at its angle (Enki's rays see both
// ways), meeting a circle of radius r at distance |along| - sqrt(r^2 -
// across^2) (0 from inside), where `along` and `across` are the centre's
// coordinates along and across the ray; the ray keeps the nearest, below
// the range. `tangent[i]`: ray i's line, or the circle around the rays,
// touches an object's circle within rounding, where either answer is right.
struct Expected {
    long double distance[3];
    long double value[3];
    bool tangent[3];
};
Expected expected_rays(const Enki::IRSensor &sensor,
                       const std::vector<Enki::PhysicalObject *> &objects)
{
    Expected expected{};
    const long double aperture = 15 * pi / 180;
    const long double heading = sensor.getAbsoluteOrientation();
    const long double middle_x =
      sensor.getAbsolutePosition().x + sensor_range / 2 * std::cos(heading);
    const long double middle_y =
      sensor.getAbsolutePosition().y + sensor_range / 2 * std::sin(heading);
    const long double rays_radius = sensor_range * std::sqrt(1.25L - std::cos(aperture));
    for (int ray = 0; ray < 3; ray++) {
        long double angle = sensor.getAbsoluteOrientation() + (ray - 1) * aperture;
        long double dx = std::cos(angle), dy = std::sin(angle);
        long double nearest = sensor_range;
        for (const Enki::PhysicalObject *object : objects) {
            if (object->getHeight() < sensor_height)
                continue;
            long double vx = (long double)object->pos.x - sensor.getAbsolutePosition().x;
            long double vy = (long double)object->pos.y - sensor.getAbsolutePosition().y;
            long double r = object->getRadius();
            long double mx = (long double)object->pos.x - middle_x;
            long double my = (long double)object->pos.y - middle_y;
            long double apart = mx * mx + my * my - (r + rays_radius) * (r + rays_radius);
            if (std::abs(apart) <= 1e-10L * (r + rays_radius) * (r + rays_radius))
                expected.tangent[ray] = true;
            if (apart > 0)
                continue;
            long double across = dx * vy - dy * vx;
            long double along = std::abs(dx * vx + dy * vy);
            long double gap = r * r - across * across;
            if (std::abs(gap) <= 1e-10L * r * r)
                expected.tangent[ray] = true;
            if (gap < 0)
                continue;
            nearest = std::min(nearest, std::max(along - std::sqrt(gap), 0.0L));
        }
        expected.distance[ray] = nearest;
        expected.value[ray] = nearest < sensor_range ? response(nearest) : 0;
        if (ray == 1 && nearest < sensor_range)
            expected.value[ray] -= 2 * response(nearest / std::cos(aperture));
    }
    return expected;
}

// Whether `sensor`'s ray `ray` agrees with `expected` up to rounding.
bool agrees(const Enki::IRSensor &sensor, const Expected &expected, unsigned ray)
{
    if (expected.tangent[ray])
        return true;
    return std::abs(sensor.getRayDist(ray) - expected.distance[ray]) <= distance_tolerance &&
           std::abs(sensor.getRayValue(ray) - expected.value[ray]) <= value_tolerance;
}

// Steps both sensors with `objects` and compares their rays: bit for bit
// when `bit_for_bit` (boxes only), else each with the geometry up to
// rounding (cylinders only) or with each other up to rounding.
enum class Check { bit_for_bit, geometry, each_other };
void compare(Enki::World &world,
             FreshIRSensor &fresh,
             EnkiIRSensor &enki,
             const std::vector<Enki::PhysicalObject *> &objects,
             Check check,
             Comparison &comparison)
{
    fresh.init(step_seconds, &world);
    enki.init(step_seconds, &world);
    for (Enki::PhysicalObject *object : objects) {
        fresh.objectStep(step_seconds, &world, object);
        enki.objectStep(step_seconds, &world, object);
    }
    Expected expected{};
    if (check == Check::geometry)
        expected = expected_rays(fresh, objects);
    for (unsigned ray = 0; ray < enki.getRayCount(); ray++) {
        if (enki.getRayDist(ray) < sensor_range)
            comparison.rays_seeing++;
        bool same = false;
        switch (check) {
        case Check::bit_for_bit:
            same = same_bits(fresh.getRayDist(ray), enki.getRayDist(ray)) &&
                   same_bits(fresh.getRayValue(ray), enki.getRayValue(ray));
            break;
        case Check::geometry:
            comparison.tangents += expected.tangent[ray] ? 1 : 0;
            // Enki's sensor too, so that the geometry is Enki's.
            same = agrees(fresh, expected, ray) && agrees(enki, expected, ray);
            break;
        case Check::each_other:
            same = std::abs(fresh.getRayDist(ray) - enki.getRayDist(ray)) <= distance_tolerance &&
                   std::abs(fresh.getRayValue(ray) - enki.getRayValue(ray)) <= value_tolerance;
            break;
        }
        if (!same) {
            comparison.differences++;
            ADD_FAILURE() << "ray " << ray << ": " << fresh.getRayDist(ray) << " "
                          << fresh.getRayValue(ray) << ", Enki's " << enki.getRayDist(ray) << " "
                          << enki.getRayValue(ray) << ", expected "
                          << double(expected.distance[ray]) << " " << double(expected.value[ray]);
        }
    }
    // The sensor's place for the step is Enki's, bit for bit.
    EXPECT_TRUE(same_bits(fresh.getAbsolutePosition().x, enki.getAbsolutePosition().x));
    EXPECT_TRUE(same_bits(fresh.getAbsolutePosition().y, enki.getAbsolutePosition().y));
    EXPECT_TRUE(same_bits(fresh.getAbsoluteOrientation(), enki.getAbsoluteOrientation()));
    EXPECT_TRUE(same_bits(fresh.getAbsSmartPos().x, enki.getAbsSmartPos().x));
    EXPECT_TRUE(same_bits(fresh.getAbsSmartPos().y, enki.getAbsSmartPos().y));
}

} // namespace

// Cylinders (robots, posts, one too low to be seen) anywhere around the
// sensor, and placed so that a ray's line passes at their radius, a hair
// inside or a hair outside: both sensors give the geometry's distances.
TEST(IrSensor, SeesCylindersAsTheGeometryGives)
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
            compare(world, fresh, enki, { &object }, Check::geometry, comparison);
            trials++;
            // A ray's line at the object's radius, give or take a hair.
            double ray = robot.angle + sensor_heading + ray_offsets[trial % 3];
            Enki::Vector along(std::cos(ray), std::sin(ray));
            double reach = (sensor_range + radius) * unit(random);
            double hair = hairs[(trial / 3) % std::size(hairs)];
            object.pos = sensor + along * reach + along.perp() * (radius * (1 + hair));
            compare(world, fresh, enki, { &object }, Check::geometry, comparison);
            trials++;
        }
    }
    EXPECT_EQ(comparison.differences, 0u);
    // Enough rays saw something for the comparison to mean something, and
    // few were left to either answer.
    EXPECT_GT(comparison.rays_seeing, trials / 2);
    EXPECT_LT(comparison.tangents, trials / 4);
}

// Boxes (the arena's obstacles) around the sensor, alone (Enki's values bit
// for bit), and with several robots seen in one step: the nearest wins, as
// in Enki, up to rounding.
TEST(IrSensor, SeesBoxesAsEnkiDoesAndCrowdsUpToRounding)
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
        std::vector<Enki::PhysicalObject *> box_pointers;
        for (Enki::PhysicalObject &other : boxes)
            box_pointers.push_back(&other);
        compare(world, fresh, enki, box_pointers, Check::bit_for_bit, comparison);
        seen.insert(seen.end(), box_pointers.begin(), box_pointers.end());
        compare(world, fresh, enki, seen, Check::each_other, comparison);
        trials++;
    }
    EXPECT_EQ(comparison.differences, 0u);
    EXPECT_GT(comparison.rays_seeing, trials / 2);
    world.objects.clear();
}

// Square walls: the sensor anywhere near them, also with the sensor itself
// past a wall; its rays as Enki's up to rounding (Enki works out each ray's
// direction with a sine and cosine, the sensor turns them).
TEST(IrSensor, SeesSquareWallsAsEnkiDoesUpToRounding)
{
    Enki::World world(200, 150);
    world.takeObjectOwnership = false;
    EnkiEpuck robot(0, 0.5, false);
    FreshIRSensor fresh = make_sensor<FreshIRSensor>(&robot);
    EnkiIRSensor enki = make_sensor<EnkiIRSensor>(&robot);
    std::mt19937_64 random(9);
    std::uniform_real_distribution<double> unit(0, 1);
    unsigned rays_seeing = 0, differences = 0, inside_wall = 0;
    for (int trial = 0; trial < 4000; trial++) {
        // Within 20 cm of a wall, a few centimetres past it at times.
        double along = unit(random), off = -4 + 24 * unit(random);
        switch (trial % 4) {
        case 0: robot.pos = Enki::Point(off, 150 * along); break;
        case 1: robot.pos = Enki::Point(200 - off, 150 * along); break;
        case 2: robot.pos = Enki::Point(200 * along, off); break;
        default: robot.pos = Enki::Point(200 * along, 150 - off); break;
        }
        robot.angle = -pi + 2 * pi * unit(random);
        fresh.init(step_seconds, &world);
        enki.init(step_seconds, &world);
        fresh.wallsStep(step_seconds, &world);
        enki.wallsStep(step_seconds, &world);
        const Enki::Point sensor = enki.getAbsolutePosition();
        if (sensor.x < 0 || sensor.x > 200 || sensor.y < 0 || sensor.y > 150)
            inside_wall++;
        for (unsigned ray = 0; ray < enki.getRayCount(); ray++) {
            if (enki.getRayDist(ray) < sensor_range)
                rays_seeing++;
            if (std::abs(fresh.getRayDist(ray) - enki.getRayDist(ray)) > distance_tolerance ||
                std::abs(fresh.getRayValue(ray) - enki.getRayValue(ray)) > value_tolerance) {
                differences++;
                ADD_FAILURE() << "ray " << ray << ": " << fresh.getRayDist(ray) << " "
                              << fresh.getRayValue(ray) << ", Enki's " << enki.getRayDist(ray)
                              << " " << enki.getRayValue(ray);
            }
        }
    }
    EXPECT_EQ(differences, 0u);
    EXPECT_GT(rays_seeing, 1500u);
    EXPECT_GT(inside_wall, 40u);
}

// The noise's generator draws what glibc's rand() draws after the same
// srand, whatever the seed (0 stands for 1, seeds past INT32_MAX wrap).
TEST(IrNoise, DrawsAsRandDoes)
{
    for (uint32_t seed : { 0u, 1u, 2u, 11u, 12345u, 2147483647u, 2147483648u, 4294967295u }) {
        std::srand(seed);
        aseba::arena::IrNoise noise(seed);
        for (int draw = 0; draw < 10000; draw++)
            ASSERT_EQ(noise.next(), std::rand()) << "seed " << seed << ", draw " << draw;
    }
    std::srand(1);
    aseba::arena::IrNoise unseeded;
    for (int draw = 0; draw < 1000; draw++)
        ASSERT_EQ(unseeded.next(), std::rand());
}

// A sensor's final value and distance are Debian's IRSensor::finalize's,
// bit for bit, from the same rays and the same seed: objects near and far,
// none, and one touching the sensor (the value clamped to the maximum).
TEST(IrSensor, FinalizesAsEnkiDoes)
{
    Enki::World world(200, 200);
    world.takeObjectOwnership = false;
    EnkiEpuck robot(0, 0.5, false);
    robot.pos = Enki::Point(100, 100);
    FreshIRSensor sensor = make_sensor<FreshIRSensor>(&robot);
    Enki::PhysicalObject other;
    other.setCylindric(3.7, 4.7, 152);
    std::mt19937_64 random(13);
    std::uniform_real_distribution<double> unit(0, 1);
    unsigned seeing = 0;
    for (int trial = 0; trial < 2000; trial++) {
        robot.angle = -pi + 2 * pi * unit(random);
        double bearing = robot.angle + sensor_heading + 0.6 * (unit(random) - 0.5);
        double distance = trial % 10 == 0 ? 0 : 20 * unit(random);
        other.pos = robot.pos + Enki::Vector(std::cos(bearing), std::sin(bearing)) * distance;
        sensor.init(step_seconds, &world);
        sensor.objectStep(step_seconds, &world, &other);
        uint32_t seed = uint32_t(trial * 7919);
        std::srand(seed);
        sensor.Enki::IRSensor::finalize(step_seconds, &world);
        double enki_value = sensor.getValue(), enki_distance = sensor.getDist();
        aseba::arena::seed_ir_noise(seed);
        sensor.finalize(step_seconds, &world);
        ASSERT_TRUE(same_bits(sensor.getValue(), enki_value)) << "trial " << trial;
        ASSERT_TRUE(same_bits(sensor.getDist(), enki_distance)) << "trial " << trial;
        seeing += enki_value > 100;
    }
    EXPECT_GT(seeing, 200u);
}
