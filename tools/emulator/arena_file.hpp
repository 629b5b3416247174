// An arena for the simulated e-pucks: its size and colours, obstacles,
// coloured ground areas, sound sources, the robots and their batteries,
// read from a small text file (docs/arena-format.md) or built in (the
// paper's setup). Lengths are in cm, angles in degrees counter-clockwise,
// colours are red, green, blue in 0..1, times in simulated seconds; x points
// right and y up, the arena spans (0, 0) to (width, height).

#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace aseba::arena
{

struct Color {
    double red = 0;
    double green = 0;
    double blue = 0;
};

// A coloured part of the floor; later areas paint over earlier ones.
struct GroundArea {
    enum class Shape { rectangle, disc };
    Shape shape = Shape::rectangle;
    double x = 0; // rectangle: lower-left corner; disc: centre
    double y = 0;
    double width = 0; // rectangle only
    double height = 0;
    double radius = 0; // disc only
    Color color;
    // A robot that stays in the area gets a knock every this many seconds
    // (0: never), as the paper's experimenter knocked robots on dangerous
    // areas (docs/arena-format.md).
    double shock_period = 0;
    // Whether the floor point (px, py) lies in the area.
    bool contains(double px, double py) const;
};

// A fixed obstacle, taller than the robots.
struct Obstacle {
    enum class Shape { box, cylinder };
    Shape shape = Shape::box;
    double x = 0; // centre
    double y = 0;
    double length = 0; // box: along its heading
    double width = 0;
    double radius = 0; // cylinder only
    double heading_degrees = 0;
    Color color;
};

// A loudspeaker playing a tone, heard by every robot's microphones.
struct SoundSource {
    // The distance at which `level` is heard (cm).
    static constexpr double reference_distance = 10;
    static constexpr double never = std::numeric_limits<double>::infinity();

    double x = 0;
    double y = 0;
    double frequency = 1000; // Hz
    // The amplitude, in ADC counts, that a microphone reads at
    // reference_distance; it falls as 1 / distance.
    double level = 0;
    double start = 0;    // when it first sounds
    double stop = never; // when it stops for good
    double beep_on = 0;  // beeps: this long on, then beep_off off, from
    double beep_off = 0; // `start`; 0: a continuous tone
    // Whether it sounds at time `seconds`.
    bool sounding(double seconds) const;
};

// The robots' battery: one Li-ion cell, drained by a constant current and
// by each motor whose coils are powered (docs/arena-format.md).
struct BatteryModel {
    double capacity_mah = 1350; // about the e-puck's 5 Wh at 3.7 V
    double idle_ma = 120;       // processor, radio, sensors
    double motor_ma = 150;      // per motor turning
};

struct RobotPlacement {
    // A robot without a stored node id answers as the chip decides: from its
    // selector, (selector & 7) + 1 (docs/arena-format.md).
    static constexpr uint16_t node_id_from_selector = 0;

    uint16_t node_id = 1; // or node_id_from_selector
    double x = 0;
    double y = 0;
    double heading_degrees = 0; // 0 = facing +x
    uint16_t selector = 0;      // position of the rotary selector, 0..15
    double battery_charge = 1;  // at start, a fraction of the full charge
};

struct Arena {
    double width = 100;
    double height = 100;
    Color wall_color{ 0.3, 0.3, 0.3 };
    Color floor_color{ 0.2, 0.2, 0.2 };
    // How far the modelled camera looks down (docs/arena-format.md).
    double camera_tilt_degrees = 30;
    // Relative noise on wheel speeds, as Enki's e-puck (uniform ±).
    double wheel_noise = 0.05;
    std::vector<GroundArea> areas;
    std::vector<Obstacle> obstacles;
    std::vector<SoundSource> sounds;
    BatteryModel battery;
    std::vector<RobotPlacement> robots;

    // The floor's colour at (x, y): the last area containing it, else the floor.
    Color ground_color(double x, double y) const;
};

// Parses arena text; throws std::runtime_error naming `source` and the line.
Arena parse_arena(const std::string &text, const std::string &source);

// Reads and parses the arena file at `path`; throws std::runtime_error.
Arena read_arena_file(const std::string &path);

// The built-in arena of the paper's setup: a square arena, three coloured
// ground areas (red, green, blue) and `robots` e-pucks (the paper had 6);
// for more robots than fit the 1 m square, the square and its areas grow so
// that each robot has about 20 cm x 20 cm.
Arena default_arena(size_t robots = 6);

// Keeps the arena's first `count` robots, or adds robots on a grid of free
// places (clear of walls, obstacles and each other) until there are `count`;
// node ids continue after the highest one. Throws std::runtime_error when
// they do not fit.
void set_robot_count(Arena &arena, size_t count);

// Draws every robot's position and heading from `seed`: uniformly over the
// arena, clear of the walls, the obstacles, the other robots and every
// ground area (the robots start off the coloured floor); ids, selectors and
// batteries stay. The same seed gives the same places. Throws
// std::runtime_error when a robot finds no free place.
void draw_start_positions(Arena &arena, uint32_t seed);

} // namespace aseba::arena
