// The e-pucks' physical world: one Enki world (Debian libenki) holding the
// arena and its robots, and for each robot a host_world (host_world.h) that
// turns Enki's state into what the robot's pins, ADC, I2C camera and pixel
// port show (and the sound field, its selector, remote receiver and
// battery into its microphones and input pins), and turns the motor phases
// its firmware drives into wheel speeds. The model and its choices are
// described in docs/arena-format.md.
//
// Debian's Enki 1.6.99 has three defects (../shared/research/enki.md),
// handled here:
// - IR values stick after an obstacle leaves: our IR sensor clears its rays
//   at the start of every step.
// - Enki's EPuck carries a hidden scanner turret that costs 2.5x in speed:
//   our robot is built on DifferentialWheeled with the e-puck's sensors only.
// - The collision depth reads 0 after a step: our robot reads it in its
//   controlStep, before Enki clears it.
// Enki visits its objects in address order; the robots and obstacles live in
// one block, in arena order, so that a run repeats bit for bit.

#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <enki/PhysicalEngine.h>
#include <enki/interactions/CircularCam.h>
#include <enki/interactions/IRSensor.h>
#include <enki/robots/DifferentialWheeled.h>

#include "arena_file.hpp"
#include "battery.hpp"
#include "partitioned_world.hpp"
#include "remote_control.hpp"
#include "sound_field.hpp"

extern "C" {
#include "boards/epuck_host/host_world.h"
}

namespace aseba::arena
{

// The IR sensors' noise: what glibc's rand() draws after srand(seed) (its
// additive feedback generator of degree 31 and separation 3, seeded as
// glibc seeds it), for the sensors' noise that Debian's Enki draws from
// rand(), without the lock and the two calls of each of glibc's draws. One
// a thread, seeded by seed_ir_noise: the worlds of a thread share it as
// those of a process shared rand(), and the noise is drawn on the thread
// that steps the world (partitioned_world.hpp).
class IrNoise
{
  public:
    static constexpr int32_t maximum = 2147483647; // glibc's RAND_MAX

    constexpr explicit IrNoise(uint32_t seed = 1)
    {
        reseed(seed);
    }
    // srand(seed).
    constexpr void reseed(uint32_t seed)
    {
        // glibc's srandom_r: 16807 times the previous word modulo 2^31 - 1
        // (Schrage's method), then 310 draws thrown away.
        int32_t word = int32_t(seed == 0 ? 1 : seed);
        state_[0] = word;
        for (unsigned i = 1; i < degree; i++) {
            long hi = word / 127773;
            long lo = word % 127773;
            word = int32_t(16807 * lo - 2836 * hi);
            if (word < 0)
                word += 2147483647;
            state_[i] = word;
        }
        front_ = separation;
        rear_ = 0;
        for (unsigned i = 0; i < 10 * degree; i++)
            next();
    }
    // rand(): 0 to maximum.
    constexpr int32_t next()
    {
        uint32_t sum = uint32_t(state_[front_]) + uint32_t(state_[rear_]);
        state_[front_] = int32_t(sum);
        front_ = front_ + 1 == degree ? 0 : front_ + 1;
        rear_ = rear_ + 1 == degree ? 0 : rear_ + 1;
        return int32_t(sum >> 1);
    }

  private:
    static constexpr unsigned degree = 31;
    static constexpr unsigned separation = 3;
    std::array<int32_t, degree> state_{};
    unsigned front_ = separation;
    unsigned rear_ = 0;
};

// This thread's IR noise; seed_ir_noise(seed) where Enki's users call
// srand(seed).
IrNoise &ir_noise();
void seed_ir_noise(uint32_t seed);

// Enki's IR sensor with its rays cleared at the start of every step, so
// that a value falls back once the obstacle has gone. For a cylinder (a
// robot, a post) it works out Enki's geometry without Enki's trigonometry
// (an arc tangent and a sine a ray): where a ray's line passes from the
// centre by a cross product with the ray's direction, and how far along by
// a dot product, so that its distances differ from Enki's by rounding only
// (about 1e-13 cm; docs/arena-format.md). Boxes go through Enki's own test,
// for the rays that may reach them. The square walls likewise: Enki's
// geometry with the rays' directions of the step rather than a sine and
// cosine a ray.
class FreshIRSensor : public Enki::IRSensor
{
  public:
    // Enki's IRSensor's parameters, in its order.
    FreshIRSensor(Enki::Robot *robot,
                  Enki::Vector position,
                  double sensor_height,
                  double heading,
                  double reach,
                  double response_maximum,
                  double response_x0,
                  double response_c,
                  double noise_sd);
    void init(double dt, Enki::World *world) override;
    void objectStep(double dt, Enki::World *world, Enki::PhysicalObject *object) override;
    // objectStep for an object as tall as the sensor or taller, its radius
    // and shape given.
    void see(double dt,
             Enki::World *world,
             Enki::PhysicalObject *object,
             double radius,
             bool cylindric);
    void wallsStep(double dt, Enki::World *world) override;
    // Debian's IRSensor::finalize, its noise drawn from ir_noise().
    void finalize(double dt, Enki::World *world) override;
    // init() given the rotation of the owner's heading, shared by its sensors.
    void start_step(const Enki::Matrix22 &owner_rotation);

    static constexpr unsigned ray_count = 3;

  private:
    // Enki's updateRay and responseFunction, inlined.
    void update_ray(unsigned ray, double distance);
    double response(double distance) const;

    // The rays' unit directions on the robot, and in the world this step.
    std::array<Enki::Vector, ray_count> ray_directions_;
    std::array<Enki::Vector, ray_count> world_ray_directions_;
};

// An e-puck in Enki: Enki's e-puck body, wheels, 8 IR sensors and camera,
// without the scanner turret; it also measures the impact of collisions.
class EnkiEpuck : public Enki::DifferentialWheeled
{
  public:
    static constexpr unsigned ir_count = 8;
    static constexpr unsigned camera_pixels = 60;

    // Enki steps the camera only when `camera_used`.
    EnkiEpuck(double wheel_noise, double camera_half_field_radians, bool camera_used);

    // The sensors Enki steps for this robot: the 8 IR sensors, the camera
    // when used, and no hidden turret.
    size_t sensor_count() const
    {
        return localInteractions.size();
    }

    std::array<FreshIRSensor, ir_count> infrared;
    Enki::CircularCam camera;

    // The velocity change (cm/s², world frame) of the impact in the last
    // step: a contact that began in that step, else zero.
    Enki::Vector impact;
    // How deep the robot went into an obstacle in the last step (cm), read
    // before Enki clears it.
    double collision_depth = 0;
    // Collisions reported by Enki in the last step.
    unsigned collisions = 0;

  protected:
    // Enki's, with the heading's sine and cosine worked out once for all
    // the IR sensors.
    void initLocalInteractions(double dt, Enki::World *world) override;
    // Enki's, with the IR sensors called directly rather than through
    // their virtual objectStep.
    void doLocalInteractions(double dt, Enki::World *world, Enki::PhysicalObject *object) override;
    void applyForces(double dt) override;
    void controlStep(double dt) override;
    void collisionEvent(Enki::PhysicalObject *other) override;

  private:
    Enki::Vector commanded_velocity_;
    bool touching_ = false;
    unsigned collisions_this_step_ = 0;
};

struct Pose {
    double x = 0; // cm
    double y = 0;
    double heading = 0; // radians, counter-clockwise from +x
};

class EnkiWorld
{
  public:
    // The simulated time one step covers (Enki's header advises 20-100 ms;
    // 10 ms keeps impacts sharp and wheel steps fine).
    static constexpr double step_seconds = 0.01;
    // How long the accelerometer keeps feeling an impact: the body rings for
    // a few milliseconds, and the firmware samples at 256 Hz.
    static constexpr unsigned impact_steps = 2;
    // The knock a robot gets on a shock area (cm/s², pointing backward, as
    // a tap on its front): 2 g, clearly above the annex's 1.3 g threshold.
    static constexpr double knock_acceleration = 2 * 981.0;

    // Builds the arena's world; `seed` seeds every random draw (wheel and IR
    // noise).
    EnkiWorld(const Arena &arena, uint32_t seed);
    ~EnkiWorld();
    EnkiWorld(const EnkiWorld &) = delete;
    EnkiWorld &operator=(const EnkiWorld &) = delete;

    size_t robot_count() const;
    const Arena &arena() const
    {
        return arena_;
    }

    // What robot `index`'s board sees; valid while this world lives.
    const host_world *world_of(size_t index) const;

    // Sets each robot's wheel speeds from the motor steps its firmware made
    // since the last step, then advances the physics and sensors by
    // step_seconds, and knocks robots that stayed long enough on shock
    // areas.
    void step();

    // Lets a step share out the robots' sensing (the most of Enki's step)
    // through `parallel_for`; a step gives the same result either way.
    void set_parallel_for(PartitionedWorld::ParallelFor parallel_for);

    // Steps done since the start.
    uint64_t steps() const
    {
        return steps_;
    }

    Pose pose(size_t index) const;
    // Moves robot `index` (tests); its sensors see the change after a step.
    void place(size_t index, const Pose &pose);
    EnkiEpuck &robot(size_t index);
    // Wheel speeds (cm/s) given to Enki at the last step.
    double left_wheel_speed(size_t index) const;
    double right_wheel_speed(size_t index) const;

    // The colours robot `index`'s modelled camera sees on `row` (0 = top of
    // the 120-row window), 120 pixels from left to right, into `pixels`;
    // with `pixel_step` 2, pixels 0, 2, 4... only (the others untouched).
    void camera_row(size_t index, unsigned row, Color *pixels, unsigned pixel_step = 1) const;

    // The boards' time at the end of the last step, in processor cycles
    // (HOST_CYCLES_PER_SECOND a second).
    uint64_t cycles() const;

    // Turns robot `index`'s selector to `position` (0..15); its firmware
    // reads the new position from the pins at once.
    void set_selector(size_t index, uint16_t position);
    uint16_t selector(size_t index) const;

    // Robot `index`'s IR receiver sees `frame` from now on (after the frames
    // it is already seeing).
    void send_rc5(size_t index, const Rc5Frame &frame);

    const Battery &battery(size_t index) const;

    const SoundField &sound_field() const
    {
        return sound_field_;
    }

    struct RobotState; // per robot: motor phases, emitters, camera registers

    // Something a camera's floor ray may meet before the floor: a robot or
    // an obstacle, taller than the camera.
    struct Occluder {
        bool box = false;
        Enki::Point centre;
        double radius = 0; // circle; for a box, its bounding circle
        double half_length = 0, half_width = 0;
        double cosine = 1, sine = 0; // a box's heading
        Color color;
    };

  private:
    // Buckets the robots' centres into square cells, for the camera to find
    // the robots near its lens (after every move of the robots).
    void build_robot_grid();

    double shock_period_at(const Enki::Point &point) const;
    // After Enki's step: robot `index`'s shocks, impacts and readings.
    void read_robot(size_t index);
    // Works out the robot's ADC readings from the world after a step.
    void update_readings(RobotState &state);
    // Places the robot's microphones where its body is now.
    void place_microphones(RobotState &state);

    Arena arena_;
    SoundField sound_field_;
    std::unique_ptr<PartitionedWorld> world_;
    // Robots then obstacles, constructed in place in one block.
    void *objects_block_ = nullptr;
    std::vector<EnkiEpuck *> robots_;
    std::vector<Enki::PhysicalObject *> obstacles_;
    std::vector<std::unique_ptr<RobotState>> states_;
    uint64_t steps_ = 0;
    // The obstacles as the camera sees them, in arena order.
    std::vector<Occluder> obstacle_occluders_;
    // The robots by cell: cell c holds robot_cells_[robot_cell_starts_[c]
    // .. robot_cell_starts_[c + 1]), ascending.
    double robot_cell_size_ = 1;
    long robot_columns_ = 1, robot_rows_ = 1;
    std::vector<uint32_t> robot_cell_starts_;
    std::vector<uint32_t> robot_cells_;
    PartitionedWorld::ParallelFor parallel_for_;
};

// Converts an Enki IR value (0..3731, as a real sensor's reflected light)
// to the phototransistor's ADC reading with its emitter lit; `ambient` is
// the reading with the emitter off.
uint16_t proximity_lit_reading(double enki_value, uint16_t ambient);

// The accelerometer's ADC reading on `axis` (0 X, 1 Y, 2 Z) for an
// acceleration `forward`, `leftward` (cm/s², robot frame) of an upright robot.
uint16_t accelerometer_reading(unsigned axis, double forward, double leftward);

} // namespace aseba::arena
