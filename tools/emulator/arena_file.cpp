// Arena files: one statement a line (docs/arena-format.md), and the built-in
// arena of the paper's setup.

#include "arena_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>

namespace aseba::arena
{
namespace
{

constexpr double pi = 3.14159265358979323846;
constexpr double degrees_per_radian = 180 / pi;
// An e-puck's body radius (cm), and the room a robot placed on a grid needs.
constexpr double robot_radius = 3.7;
constexpr double grid_spacing = 10;
constexpr double placement_clearance = 1;

// The default arena: a 1 m square (the scale of the paper's photographs),
// each robot given about 20 cm x 20 cm when there are more than fit.
constexpr double default_side = 100;
constexpr double room_per_robot = 20;
constexpr double default_area_radius = 14; // fraction of a 100 cm side, scaled

// The microphones are sampled 16384 times a second (robots/epuck): a tone
// above half that would alias.
constexpr double highest_frequency = 8192;
constexpr unsigned selector_positions = 16;
// Draws before drawn start positions give up on a robot.
constexpr int placement_attempts = 10000;

bool inside_unit(double value)
{
    return value >= 0 && value <= 1;
}

class LineReader
{
  public:
    LineReader(const std::string &line, const std::string &where)
      : stream_(line)
      , where_(where)
    {
    }

    std::string word()
    {
        std::string text;
        if (!(stream_ >> text))
            fail("missing value");
        return text;
    }

    double number(const char *what)
    {
        return number_from(word(), what);
    }

    double number_from(const std::string &text, const char *what)
    {
        char *end = nullptr;
        double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(value))
            fail(std::string(what) + " must be a number, not '" + text + "'");
        return value;
    }

    double positive(const char *what)
    {
        double value = number(what);
        if (value <= 0)
            fail(std::string(what) + " must be above 0");
        return value;
    }

    double not_negative(const char *what)
    {
        double value = number(what);
        if (value < 0)
            fail(std::string(what) + " must not be below 0");
        return value;
    }

    // The next option word of a statement, each allowed once.
    std::string option()
    {
        std::string name = word();
        if (!options_seen_.insert(name).second)
            fail("'" + name + "' is given twice");
        return name;
    }

    Color color()
    {
        Color color;
        color.red = number("red");
        color.green = number("green");
        color.blue = number("blue");
        if (!inside_unit(color.red) || !inside_unit(color.green) || !inside_unit(color.blue))
            fail("colour components go from 0 to 1");
        return color;
    }

    bool more()
    {
        return !(stream_ >> std::ws).eof();
    }

    void end()
    {
        std::string extra;
        if (stream_ >> extra)
            fail("unexpected '" + extra + "'");
    }

    [[noreturn]] void fail(const std::string &message) const
    {
        throw std::runtime_error(where_ + ": " + message);
    }

  private:
    std::istringstream stream_;
    std::string where_;
    std::set<std::string> options_seen_;
};

RobotPlacement parse_robot(LineReader &read)
{
    RobotPlacement robot;
    std::string id = read.word();
    if (id == "-") {
        robot.node_id = RobotPlacement::node_id_from_selector;
    } else {
        double number = read.number_from(id, "node id");
        if (number < 1 || number > 0xFFFE || number != std::floor(number))
            read.fail("a node id is a whole number from 1 to 65534, or '-'");
        robot.node_id = uint16_t(number);
    }
    robot.x = read.number("x");
    robot.y = read.number("y");
    robot.heading_degrees = read.number("heading");
    while (read.more()) {
        std::string option = read.option();
        if (option == "selector") {
            double position = read.number("selector");
            if (position < 0 || position >= selector_positions || position != std::floor(position))
                read.fail("the selector goes from 0 to 15");
            robot.selector = uint16_t(position);
        } else if (option == "battery") {
            double percent = read.number("battery charge");
            if (!(percent > 0 && percent <= 100))
                read.fail("a battery charge goes from above 0 to 100 %");
            robot.battery_charge = percent / 100;
        } else {
            read.fail("expected 'selector N' or 'battery PERCENT' after the heading, not '" +
                      option + "'");
        }
    }
    return robot;
}

SoundSource parse_sound(LineReader &read)
{
    SoundSource sound;
    sound.x = read.number("x");
    sound.y = read.number("y");
    sound.frequency = read.positive("frequency");
    if (sound.frequency > highest_frequency)
        read.fail("the microphones hear up to 8192 Hz, half their sampling rate");
    sound.level = read.positive("level");
    while (read.more()) {
        std::string option = read.option();
        if (option == "start") {
            sound.start = read.not_negative("start");
        } else if (option == "stop") {
            sound.stop = read.positive("stop");
        } else if (option == "beep") {
            sound.beep_on = read.positive("beep on time");
            sound.beep_off = read.positive("beep off time");
        } else {
            read.fail("expected 'start S', 'stop S' or 'beep ON OFF' after the level, not '" +
                      option + "'");
        }
    }
    if (sound.stop <= sound.start)
        read.fail("a sound stops after it starts");
    return sound;
}

bool inside(const Arena &arena, double x, double y)
{
    return x >= 0 && y >= 0 && x <= arena.width && y <= arena.height;
}

// Whether a robot at (x, y) is clear of the walls, the obstacles and the
// robots `others`.
bool robot_fits(const Arena &arena, const std::vector<RobotPlacement> &others, double x, double y)
{
    double margin = robot_radius + placement_clearance;
    if (x < margin || y < margin || x > arena.width - margin || y > arena.height - margin)
        return false;
    for (const RobotPlacement &robot : others)
        if (std::hypot(robot.x - x, robot.y - y) < 2 * margin)
            return false;
    for (const Obstacle &obstacle : arena.obstacles) {
        // A bounding circle is enough to keep placements clear.
        double reach = obstacle.shape == Obstacle::Shape::cylinder
                         ? obstacle.radius
                         : std::hypot(obstacle.length, obstacle.width) / 2;
        if (std::hypot(obstacle.x - x, obstacle.y - y) < reach + margin)
            return false;
    }
    return true;
}

// Whether a robot's body at (x, y) touches no ground area.
bool off_the_areas(const Arena &arena, double x, double y)
{
    for (const GroundArea &area : arena.areas) {
        double gap;
        if (area.shape == GroundArea::Shape::disc) {
            gap = std::hypot(x - area.x, y - area.y) - area.radius;
        } else {
            double dx = std::max({ area.x - x, 0.0, x - (area.x + area.width) });
            double dy = std::max({ area.y - y, 0.0, y - (area.y + area.height) });
            gap = std::hypot(dx, dy);
        }
        if (gap <= robot_radius)
            return false;
    }
    return true;
}

} // namespace

bool SoundSource::sounding(double seconds) const
{
    if (seconds < start || seconds >= stop)
        return false;
    if (beep_on <= 0)
        return true;
    return std::fmod(seconds - start, beep_on + beep_off) < beep_on;
}

bool GroundArea::contains(double px, double py) const
{
    if (shape == Shape::disc) {
        // Outside the disc's square, hypot can only be larger than the
        // radius: the cheap test first.
        if (std::abs(px - x) > radius || std::abs(py - y) > radius)
            return false;
        return std::hypot(px - x, py - y) <= radius;
    }
    return px >= x && px <= x + width && py >= y && py <= y + height;
}

Color Arena::ground_color(double x, double y) const
{
    for (auto area = areas.rbegin(); area != areas.rend(); ++area)
        if (area->contains(x, y))
            return area->color;
    return floor_color;
}

Arena parse_arena(const std::string &text, const std::string &source)
{
    Arena arena;
    arena.robots.clear();
    std::istringstream lines(text);
    std::string line;
    unsigned number = 0;
    bool sized = false;
    while (std::getline(lines, line)) {
        number++;
        line = line.substr(0, line.find('#'));
        if (line.find_first_not_of(" \t\r") == std::string::npos)
            continue;
        LineReader read(line, source + ":" + std::to_string(number));
        std::string keyword = read.word();
        if (keyword == "size") {
            arena.width = read.positive("width");
            arena.height = read.positive("height");
            sized = true;
        } else if (keyword == "walls") {
            arena.wall_color = read.color();
        } else if (keyword == "floor") {
            arena.floor_color = read.color();
        } else if (keyword == "camera-tilt") {
            arena.camera_tilt_degrees = read.number("tilt");
            if (arena.camera_tilt_degrees < 0 || arena.camera_tilt_degrees >= 90)
                read.fail("the camera tilt goes from 0 to below 90 degrees");
        } else if (keyword == "wheel-noise") {
            arena.wheel_noise = read.number("noise");
            if (arena.wheel_noise < 0 || arena.wheel_noise >= 1)
                read.fail("the wheel noise goes from 0 to below 1");
        } else if (keyword == "area") {
            GroundArea area;
            std::string shape = read.word();
            area.x = read.number("x");
            area.y = read.number("y");
            if (shape == "rectangle") {
                area.shape = GroundArea::Shape::rectangle;
                area.width = read.positive("width");
                area.height = read.positive("height");
            } else if (shape == "disc") {
                area.shape = GroundArea::Shape::disc;
                area.radius = read.positive("radius");
            } else {
                read.fail("an area is a rectangle or a disc, not '" + shape + "'");
            }
            area.color = read.color();
            if (read.more()) {
                std::string option = read.word();
                if (option != "shock")
                    read.fail("expected 'shock SECONDS' after the colour, not '" + option + "'");
                area.shock_period = read.positive("shock period");
            }
            arena.areas.push_back(area);
        } else if (keyword == "obstacle") {
            Obstacle obstacle;
            std::string shape = read.word();
            obstacle.x = read.number("x");
            obstacle.y = read.number("y");
            if (shape == "box") {
                obstacle.shape = Obstacle::Shape::box;
                obstacle.length = read.positive("length");
                obstacle.width = read.positive("width");
                obstacle.heading_degrees = read.number("heading");
            } else if (shape == "cylinder") {
                obstacle.shape = Obstacle::Shape::cylinder;
                obstacle.radius = read.positive("radius");
            } else {
                read.fail("an obstacle is a box or a cylinder, not '" + shape + "'");
            }
            obstacle.color = read.color();
            arena.obstacles.push_back(obstacle);
        } else if (keyword == "sound") {
            arena.sounds.push_back(parse_sound(read));
        } else if (keyword == "battery") {
            arena.battery.capacity_mah = read.positive("capacity");
            if (read.more()) {
                arena.battery.idle_ma = read.not_negative("idle current");
                arena.battery.motor_ma = read.not_negative("motor current");
            }
        } else if (keyword == "robot") {
            RobotPlacement robot = parse_robot(read);
            for (const RobotPlacement &other : arena.robots)
                if (robot.node_id != RobotPlacement::node_id_from_selector &&
                    other.node_id == robot.node_id)
                    read.fail("node id " + std::to_string(robot.node_id) + " is used twice");
            arena.robots.push_back(robot);
        } else {
            read.fail("unknown statement '" + keyword + "'");
        }
        read.end();
    }
    if (!sized)
        throw std::runtime_error(source + ": no 'size' statement");
    for (size_t i = 0; i < arena.robots.size(); i++) {
        const RobotPlacement &robot = arena.robots[i];
        if (!inside(arena, robot.x, robot.y))
            throw std::runtime_error(source + ": robot " +
                                     (robot.node_id != RobotPlacement::node_id_from_selector
                                        ? std::to_string(robot.node_id)
                                        : "number " + std::to_string(i + 1) + " (id '-')") +
                                     " stands outside the arena");
    }
    for (size_t i = 0; i < arena.sounds.size(); i++)
        if (!inside(arena, arena.sounds[i].x, arena.sounds[i].y))
            throw std::runtime_error(source + ": sound " + std::to_string(i + 1) +
                                     " stands outside the arena");
    return arena;
}

Arena read_arena_file(const std::string &path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
        throw std::runtime_error("cannot read arena file '" + path + "'");
    std::ostringstream text;
    text << file.rdbuf();
    return parse_arena(text.str(), path);
}

Arena default_arena(size_t robots)
{
    Arena arena;
    double side = std::max(default_side, room_per_robot * std::ceil(std::sqrt(double(robots))));
    double scale = side / default_side;
    arena.width = side;
    arena.height = side;
    // Light colours on a dark floor: the annex counts a colour only when
    // the mean of its camera means is above 38 of 93 (examples/README.md).
    const Color red{ 1.0, 0.3, 0.3 }, green{ 0.3, 1.0, 0.3 }, blue{ 0.3, 0.3, 1.0 };
    const double area_radius = default_area_radius * scale;
    auto disc = [&](double x, double y, Color color) {
        GroundArea area;
        area.shape = GroundArea::Shape::disc;
        area.x = x * scale;
        area.y = y * scale;
        area.radius = area_radius;
        area.color = color;
        arena.areas.push_back(area);
    };
    disc(22, 78, red);
    disc(78, 78, green);
    disc(50, 20, blue);
    // The experimenter knocks robots on red as soon as they are on it, and
    // again while they stay: every 0.25 s, the first 3 cm in at full speed.
    // A knock only after 1 s came 13 cm into the disc, where the camera sees
    // red all around and the annex turns on the spot for good
    // (docs/experiment.md).
    constexpr double red_shock_period = 0.25;
    arena.areas[0].shock_period = red_shock_period;
    // The paper's 6 robots start on a ring around the centre, facing out.
    constexpr size_t ring_robots = 6;
    constexpr double ring_radius = 12;
    for (size_t i = 0; i < std::min(robots, ring_robots); i++) {
        double heading = 360.0 * double(i) / double(ring_robots) + 30;
        RobotPlacement robot;
        robot.node_id = uint16_t(i + 1);
        robot.x = side / 2 + ring_radius * std::cos(heading / degrees_per_radian);
        robot.y = side / 2 + ring_radius * std::sin(heading / degrees_per_radian);
        robot.heading_degrees = heading;
        arena.robots.push_back(robot);
    }
    set_robot_count(arena, robots);
    return arena;
}

void set_robot_count(Arena &arena, size_t count)
{
    if (arena.robots.size() >= count) {
        arena.robots.resize(count);
        return;
    }
    uint32_t next_id = 1;
    for (const RobotPlacement &robot : arena.robots)
        next_id = std::max<uint32_t>(next_id, robot.node_id + 1u);
    // Free grid places, row by row; headings vary so that robots spread out.
    constexpr double heading_step = 137;
    for (double y = grid_spacing / 2; y < arena.height && arena.robots.size() < count;
         y += grid_spacing) {
        for (double x = grid_spacing / 2; x < arena.width && arena.robots.size() < count;
             x += grid_spacing) {
            if (!robot_fits(arena, arena.robots, x, y))
                continue;
            if (next_id > 0xFFFE)
                throw std::runtime_error("no node ids left for more robots");
            RobotPlacement robot;
            robot.node_id = uint16_t(next_id++);
            robot.x = x;
            robot.y = y;
            robot.heading_degrees = std::fmod(heading_step * double(robot.node_id), 360.0);
            arena.robots.push_back(robot);
        }
    }
    if (arena.robots.size() < count)
        throw std::runtime_error("only " + std::to_string(arena.robots.size()) +
                                 " robots fit in the arena, not " + std::to_string(count));
}

void draw_start_positions(Arena &arena, uint32_t seed)
{
    // A generator of its own, fixed by the standard, so that the places do
    // not depend on the library's distributions nor on Enki's draws.
    std::mt19937 generator(seed);
    auto uniform = [&generator] {
        constexpr double range = 4294967296.0; // 2^32: mt19937 gives 32 bits
        return (double(generator()) + 0.5) / range;
    };
    std::vector<RobotPlacement> placed;
    for (RobotPlacement robot : arena.robots) {
        int attempt = 0;
        do {
            if (++attempt > placement_attempts)
                throw std::runtime_error("no free place off the coloured areas for robot " +
                                         std::to_string(placed.size() + 1) + " of " +
                                         std::to_string(arena.robots.size()) + " after " +
                                         std::to_string(placement_attempts) + " draws");
            robot.x = uniform() * arena.width;
            robot.y = uniform() * arena.height;
        } while (!robot_fits(arena, placed, robot.x, robot.y) ||
                 !off_the_areas(arena, robot.x, robot.y));
        robot.heading_degrees = uniform() * 360;
        placed.push_back(robot);
    }
    arena.robots = placed;
}

} // namespace aseba::arena
