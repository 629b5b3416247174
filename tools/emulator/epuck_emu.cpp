// epuck-emu: the e-puck firmware image running on a PC. Each robot is the
// real firmware (VM, natives, protocol node) on a simulated board; together
// they form one Aseba network that tools reach over TCP.

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <thread>
#include <memory>
#include <optional>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>
#include <string>
#include <vector>

#include "arena_control.hpp"
#include "arena_feed.hpp"
#include "arena_file.hpp"
#include "arena_simulation.hpp"
#include "dspic30_arena.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"
#include "control_port.hpp"
#include "network.hpp"
#include "network_status.hpp"
#include "robot_memory.hpp"
#include "tools/command_line/command_line.hpp"
#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "ports/host/host_robot.h"
}

namespace
{

const char *const USAGE = "usage: epuck-emu [options]";

const char *const DESCRIPTION =
  R"(Runs simulated e-puck robots, each with the real firmware, as one Aseba
network (protocol 5) that Aseba Studio, asebamassloader, asebacmd and the
other Aseba tools reach over TCP, as they would reach real robots behind a
Bluetooth switch.

The network listens on the loopback interface only (127.0.0.1): tools of
this computer reach it, nothing else does. Aseba has no authentication (nor
has the robots' Bluetooth link): whoever reaches the port can stop,
reprogram, reboot or flash every robot and speak as any node. --listen
ADDRESS opens it to other computers, e.g. --listen 0.0.0.0 for every
interface (docs/threat-model.md).

At power-on each robot's bootloader decides, as on the chip: with a valid
application image in its flash, the firmware starts at once and runs the
program stored there (or --load's); a robot whose image is not valid (an
interrupted flashing, kept with --memory) stays in its bootloader, waiting
for an image. REBOOT (Studio, `aseba reboot`, `aseba flash`) resets it as on
the chip: its Aseba bootloader runs, answers the bootloader messages for 1 s
(longer once a host addresses it), then starts the application if the
flashed image is valid. The PC cannot execute dsPIC code: a valid image runs
this build's firmware.

Without --arena, the robots stand in a flat, empty world (no physics): their
drivers read neutral sensor values (no obstacle, robot level, silence),
ir_sensors fires after each full IR update (about 63 Hz) and timer every
timer.period ms; the flat world has no camera, so the camera event does not
fire. With --arena, the robots are in a physical world simulated by Enki,
in simulated time.)";

std::atomic<bool> stop_requested{ false };

void request_stop(int)
{
    stop_requested = true;
}

// Whether a line printed could not be written (a full disk, a closed pipe).
// That is said once on standard error; the robots go on serving their tools
// without the status line, and the run ends with EXIT_FAILED.
bool output_failed = false;

void flush_output()
{
    if (output_failed)
        return;
    errno = 0;
    if (std::fflush(stdout) == 0 && !std::ferror(stdout))
        return;
    output_failed = true;
    std::fprintf(stderr,
                 "epuck-emu: cannot write to standard output%s%s; no more status lines\n",
                 errno != 0 ? ": " : "",
                 errno != 0 ? std::strerror(errno) : "");
}

// The exit status of a run whose memories were kept (or not) as asked.
int exit_status(bool memories_failed)
{
    flush_output();
    return memories_failed || output_failed ? aseba::command_line::EXIT_FAILED
                                            : aseba::command_line::EXIT_OK;
}

struct Options {
    uint16_t port = 33333;
    std::string listen_address = aseba::host::LOOPBACK_ADDRESS;
    uint16_t robot_ports = 0; // the first robot's own port; 0: none
    unsigned robots = 1;
    double duration_seconds = 0;
    std::string load;
    std::string node;
    bool quiet = false;
    std::string arena;
    std::string firmware;
    std::string memory_folder;
    bool robots_given = false;
    uint32_t seed = 1;
    bool realtime = false;
    bool drawn_starts = false;
    uint16_t control_port = 0; // 0: none
    uint16_t arena_feed = 0;   // port of the arena feed; 0: none
    unsigned threads = 0;      // 0: as many as pay off (firmware_threads)
    std::string dspic30_image; // arena mode: the image every robot's chip runs
};

// Robots a thread should have at least for another thread to pay off: each
// simulated millisecond the threads meet, which costs about what some tens
// of robots' millisecond of firmware does (measured on two cores, idle, the
// paper's controller: one thread ran 100 robots faster than two, 24x
// against 21x real time; two ran 150 faster than one, 16.5x against 15.6x).
constexpr size_t robots_per_thread = 64;

// Polls of one robot between two passes of the network without the arena,
// at most: enough for the frames one pass brings, few enough that a robot
// whose program never rests does not keep the network waiting.
constexpr int polls_per_pass = 32;

// The threads the arena's firmware runs on: as asked, else one per core
// while each gets enough robots.
unsigned firmware_threads(const Options &options, size_t robots)
{
    if (options.threads > 0)
        return options.threads;
    size_t cores = std::max(1u, std::thread::hardware_concurrency());
    return unsigned(std::clamp<size_t>(robots / robots_per_thread, 1, cores));
}

[[noreturn]] void fail(const std::string &message)
{
    aseba::command_line::print_usage_error("epuck-emu", message);
    std::exit(aseba::command_line::EXIT_USAGE);
}

// Opens a port: one that cannot be opened (in use, not allowed) is the work
// failing, not bad usage, so exit status 1, as for every program here.
template<typename Open>
void open_port(Open open)
{
    try {
        open();
    } catch (const std::exception &error) {
        std::fprintf(stderr, "epuck-emu: %s\n", error.what());
        std::exit(aseba::command_line::EXIT_FAILED);
    }
}

Options parse_options(int argc, char **argv)
{
    Options options;
    CLI::App app(DESCRIPTION, "epuck-emu");
    auto formatter = aseba::command_line::use_common_style(app);
    formatter->set_usage(&app, USAGE);
    app.footer(aseba::command_line::EXIT_STATUS_TEXT);
    app.add_option("--port", options.port, "TCP port of the network (default 33333)")
      ->check(CLI::Range(1, 65535).description(""))
      ->type_name("N");
    app
      .add_option("--listen",
                  options.listen_address,
                  "the address to listen on (default 127.0.0.1, this computer only);\n"
                  "0.0.0.0 or :: opens the robots to the network (see above)")
      ->type_name("ADDRESS");
    app
      .add_option("--robot-ports",
                  options.robot_ports,
                  "also give each robot a port of its own, as each robot of the\n"
                  "reference simulator has: robot i (from 0: node id i+1, or the\n"
                  "arena file's i-th robot) listens on B+i too, where a tool is linked\n"
                  "to it alone, as by Bluetooth: the tool hears that robot only and\n"
                  "reaches that robot only, while the robot's frames still reach the\n"
                  "whole network")
      ->check(CLI::Range(1, 65535).description(""))
      ->type_name("B");
    CLI::Option *robots = app
                            .add_option("--robots",
                                        options.robots,
                                        "number of robots, node ids 1..N (default 1); in arena\n"
                                        "mode, keep the file's first N robots or add robots on\n"
                                        "free places up to N (default: the file's)")
                            ->check(CLI::Range(1, 1000).description(""))
                            ->type_name("N");
    app
      .add_option("--duration",
                  options.duration_seconds,
                  "stop after S seconds (simulated seconds in arena mode; default: run\n"
                  "until interrupted)")
      ->check(CLI::Range(0.0, double(1u << 30)).description(""))
      ->type_name("S");
    app
      .add_option("--load",
                  options.load,
                  "compile FILE (an .aesl project or a script) for the e-puck and start\n"
                  "it on every robot, as if stored in the robots")
      ->type_name("FILE");
    app
      .add_option("--node",
                  options.node,
                  "in an .aesl project, the node whose program to load (default: the\n"
                  "one named e-puck, else the first)")
      ->type_name("NAME");
    app
      .add_option("--firmware",
                  options.firmware,
                  "the application image (Microchip HEX with its descriptor, as `make\n"
                  "dspic30` writes it) in every robot's flash at start (default: a\n"
                  "placeholder image that the bootloader accepts)")
      ->type_name("FILE");
    app
      .add_option("--memory",
                  options.memory_folder,
                  "keep each robot's flash and EEPROM in DIR/robot-ID.mem: loaded at\n"
                  "start when present, written at every flash or EEPROM write, so that\n"
                  "stored programs and flashed images outlive the run, even a kill -9")
      ->type_name("DIR");
    app.add_flag("--quiet", options.quiet, "no status line");
    app
      .add_option("--arena",
                  options.arena,
                  "run the arena described in FILE (docs/arena-format.md), or `default`\n"
                  "for the paper's setup: a square arena with red, green and blue\n"
                  "ground areas and 6 e-pucks")
      ->type_name("FILE|default");
    app
      .add_option("--seed",
                  options.seed,
                  "arena mode: seed of every random draw (default 1): the same arena,\n"
                  "seed and program give the same run, bit for bit, while no tool sends\n"
                  "frames")
      ->type_name("N");
    app
      .add_option("--threads",
                  options.threads,
                  "arena mode: threads that run the robots' firmware (default: one per\n"
                  "core, each with 64 robots or more); the run is the same, bit for bit,\n"
                  "whatever their number")
      ->check(CLI::Range(1, 64))
      ->type_name("N");
    std::string speed = "max";
    app
      .add_option(
        "--speed", speed, "arena mode: `max` (as fast as possible, the default) or `realtime`")
      ->check(CLI::IsMember({ "max", "realtime" }))
      ->type_name("SPEED");
    std::string starts = "placed";
    app
      .add_option("--starts",
                  starts,
                  "arena mode: `placed` (where the arena file puts the robots, the\n"
                  "default arena on its ring; the default) or `drawn` (positions and\n"
                  "headings drawn from the seed, off the coloured areas)")
      ->check(CLI::IsMember({ "placed", "drawn" }))
      ->type_name("STARTS");
    app
      .add_option("--control",
                  options.control_port,
                  "arena mode: take commands on loopback port P, one a line: turn a\n"
                  "robot's selector, press a remote key for one robot or all, status\n"
                  "(docs/arena-format.md, \"Run-time control\")")
      ->check(CLI::Range(1, 65535).description(""))
      ->type_name("P");
    app
      .add_option("--arena-feed",
                  options.arena_feed,
                  "arena mode: serve the arena's geometry and the robots' positions and\n"
                  "LEDs on port P (of the --listen address), for viewers such as\n"
                  "aseba-ide --arena (docs/ide-protocol.md)")
      ->check(CLI::Range(1, 65535).description(""))
      ->type_name("P");
    app
      .add_option("--dspic30",
                  options.dspic30_image,
                  "arena mode: run every robot on a simulated dsPIC30F6014A from the\n"
                  "Intel HEX image FILE (build/dspic30/epuck-aseba-factory.hex: the\n"
                  "bootloader and the application) instead of on the host board: the\n"
                  "real machine code, its sensors, motors and camera fed by the same\n"
                  "world (docs/dspic30-sim.md); node ids from the selector, robot i's\n"
                  "turned to i-1 (ids 1..8); --load's program is sent to each robot\n"
                  "once its firmware runs (1.5 s); no --memory, --robot-ports,\n"
                  "--control nor --arena-feed with it")
      ->type_name("FILE");
    bool headless = false; // there is no window to hide
    app.add_flag("--headless", headless, "accepted for compatibility: there is no window anyway");
    aseba::command_line::parse_or_exit(app, argc, argv);
    options.robots_given = robots->count() > 0;
    options.realtime = speed == "realtime";
    options.drawn_starts = starts == "drawn";
    return options;
}

// Where robot `node_id` keeps its memories with --memory.
std::string memory_file(const Options &options, uint16_t node_id)
{
    return options.memory_folder + "/robot-" + std::to_string(node_id) + ".mem";
}

// Fills a robot's memories before power-on: the --firmware image, then the
// memories saved by an earlier run (which win).
std::function<void(host_robot &)> memory_preparation(const Options &options)
{
    std::optional<aseba::flash::ProgramImage> image;
    if (!options.firmware.empty()) {
        try {
            image = aseba::host::read_application_file(options.firmware);
        } catch (const std::exception &error) {
            fail(error.what());
        }
    }
    if (!options.memory_folder.empty()) {
        struct stat status;
        if (stat(options.memory_folder.c_str(), &status) != 0 || !S_ISDIR(status.st_mode))
            fail("--memory: " + options.memory_folder + " is not a folder");
    }
    return [image, &options](host_robot &robot) {
        if (image)
            aseba::host::install_application(robot.board, *image);
        if (!options.memory_folder.empty())
            aseba::host::load_memories(robot.board, memory_file(options, robot.node_id));
    };
}

// With --memory, each robot's memories in their file from now on, as the
// robot changes them.
class MemoryFiles
{
  public:
    template<typename RobotAt>
    MemoryFiles(const Options &options, size_t count, RobotAt robot_at)
    {
        if (options.memory_folder.empty())
            return;
        try {
            for (size_t i = 0; i < count; i++) {
                host_robot &robot = robot_at(i);
                files_.push_back(std::make_unique<aseba::host::MemoryFile>(
                  robot.board, memory_file(options, robot.node_id)));
            }
        } catch (const std::exception &error) {
            fail(error.what());
        }
    }

    // Writes what changed; false after reporting a failure (then it stops
    // trying, and the run goes on without its memories being kept).
    bool sync()
    {
        try {
            for (auto &file : files_)
                file->sync();
            return true;
        } catch (const std::exception &error) {
            std::fprintf(
              stderr, "epuck-emu: %s; the robots' memories are no longer kept\n", error.what());
            files_.clear();
            failed_ = true;
            return false;
        }
    }

    bool failed() const
    {
        return failed_;
    }

  private:
    std::vector<std::unique_ptr<aseba::host::MemoryFile>> files_;
    bool failed_ = false;
};

// Makes sure the process may hold the most connections its ports take, so
// that filling one leaves the others reachable (exits when it cannot).
void reserve_descriptors(const Options &options, size_t robots)
{
    // Standard streams, the sanitizers' and Enki's files, a margin.
    constexpr size_t other_descriptors = 64;
    size_t needed = aseba::host::MAX_CLIENTS + 1 + other_descriptors;
    if (options.robot_ports != 0)
        needed += robots * (aseba::host::ROBOT_PORT_CLIENTS + 1);
    if (options.control_port != 0)
        needed += aseba::arena::ControlPort::most_clients + 1;
    if (options.arena_feed != 0)
        needed += aseba::arena::ArenaFeed::MOST_VIEWERS + 1;
    if (!options.memory_folder.empty())
        needed += robots;
    try {
        aseba::connections::reserve_descriptors(needed);
    } catch (const std::exception &error) {
        std::fprintf(stderr, "epuck-emu: %s\n", error.what());
        std::exit(aseba::command_line::EXIT_FAILED);
    }
}

// With --robot-ports, opens each robot's own port.
template<typename BoardAt>
void listen_robot_ports(const Options &options,
                        aseba::host::Network &network,
                        size_t count,
                        BoardAt board_at)
{
    if (options.robot_ports == 0)
        return;
    constexpr size_t highest_port = 65535;
    if (options.robot_ports + count - 1 > highest_port)
        fail("--robot-ports " + std::to_string(options.robot_ports) + " leaves no port for robot " +
             std::to_string(count));
    for (size_t i = 0; i < count; i++)
        network.listen_robot(
          &board_at(i), uint16_t(options.robot_ports + i), options.listen_address);
}

// How the start-up line tells who may connect.
std::string listen_note(const Options &options)
{
    if (options.listen_address == aseba::host::LOOPBACK_ADDRESS)
        return " (this computer only)";
    return " (open to the network on " + options.listen_address + ")";
}

// How the start-up line tells the robots' own ports, if any.
std::string robot_ports_note(const Options &options, size_t count)
{
    if (options.robot_ports == 0)
        return "";
    return " (each robot alone on tcp:port=" + std::to_string(options.robot_ports) + " to " +
           std::to_string(options.robot_ports + count - 1) + ")";
}

// The program of --load, compiled for the e-puck; exits with status 2 when
// the file cannot be read or is no valid project, with the compiler's
// message and status 1 when it does not compile.
aseba::ProgramFile load_program(const Options &options, std::vector<uint16_t> &bytecode)
{
    aseba::ProgramFile program;
    try {
        program = aseba::read_program_file(options.load, options.node);
        if (options.node.empty() && program.node_name != EPUCK_NAME) {
            // Prefer the project's e-puck program when it has several nodes.
            try {
                program = aseba::read_program_file(options.load, EPUCK_NAME);
            } catch (const std::runtime_error &) {
            }
        }
    } catch (const std::runtime_error &error) {
        std::fprintf(stderr, "%s\n", error.what());
        std::exit(aseba::command_line::EXIT_USAGE);
    }
    std::string error_text;
    aseba::CompileResult result =
      aseba::compile_program_file(program, aseba::epuck_target(), error_text);
    if (!result.ok) {
        std::fputs(error_text.c_str(), stderr);
        std::exit(aseba::command_line::EXIT_FAILED);
    }
    bytecode = result.bytecode;
    return program;
}

// What the arena feed shows of each robot: its pose, and its LEDs as the
// board's output pins drive them.
std::vector<aseba::arena::FeedRobot> feed_robots(aseba::arena::ArenaSimulation &simulation)
{
    std::vector<aseba::arena::FeedRobot> robots;
    for (size_t i = 0; i < simulation.robot_count(); i++) {
        const hal_board &board = simulation.board(i);
        aseba::arena::FeedRobot robot;
        robot.node_id = simulation.node_id(i);
        robot.pose = simulation.world().pose(i);
        for (size_t led = 0; led < robot.ring.size(); led++)
            robot.ring[led] = board.outputs[EPUCK_PIN_LED_0 + led];
        robot.body = board.outputs[EPUCK_PIN_BODY_LED];
        robot.front = board.outputs[EPUCK_PIN_FRONT_LED];
        robots.push_back(robot);
    }
    return robots;
}

// Ahead of the wall clock (`simulated` seconds against `wall_seconds()`):
// waits, serving tools meanwhile. A frame ends a wait early, so it waits
// again until the clock has caught up, or a stop is asked for.
template<typename WallSeconds>
void keep_pace(aseba::host::Network &network, double simulated, WallSeconds wall_seconds)
{
    constexpr double milliseconds_per_second = 1000;
    for (double wall = wall_seconds(); simulated > wall && !stop_requested; wall = wall_seconds())
        network.service(int(std::ceil((simulated - wall) * milliseconds_per_second)));
}

// The arena with every robot on a simulated dsPIC (dspic30_arena.hpp),
// running `bytecode` if there is one; returns the exit status.
int run_dspic30_arena(const Options &options,
                      const aseba::arena::Arena &arena,
                      const std::vector<uint16_t> &bytecode)
{
    if (!options.memory_folder.empty() || options.robot_ports != 0 || options.control_port != 0 ||
        options.arena_feed != 0)
        fail("--dspic30 takes no --memory, --robot-ports, --control nor --arena-feed");
    std::unique_ptr<aseba::arena::Dspic30Arena> simulation_owner;
    try {
        simulation_owner = std::make_unique<aseba::arena::Dspic30Arena>(
          arena, options.seed, aseba::dspic30::read_intel_hex_file(options.dspic30_image));
    } catch (const std::exception &error) {
        fail(error.what());
    }
    aseba::arena::Dspic30Arena &simulation = *simulation_owner;
    if (!bytecode.empty())
        simulation.load_at_start(bytecode);
    aseba::host::Network &network = simulation.network();
    reserve_descriptors(options, simulation.robot_count());
    open_port([&] { network.listen(options.port, options.listen_address); });
    std::printf("epuck-emu: arena %s, %zu robot%s on simulated dsPIC30F6014A chips (%s)%s%s on "
                "tcp:port=%u%s, seed %u, %s speed\n",
                options.arena.c_str(),
                simulation.robot_count(),
                simulation.robot_count() == 1 ? "" : "s",
                options.dspic30_image.c_str(),
                options.load.empty() ? "" : ", running ",
                options.load.c_str(),
                unsigned(options.port),
                listen_note(options).c_str(),
                unsigned(options.seed),
                options.realtime ? "real-time" : "maximum");
    flush_output();
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    auto wall_seconds = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
    try {
        while (!stop_requested) {
            if (options.duration_seconds > 0 && simulation.seconds() >= options.duration_seconds)
                break;
            simulation.step();
            if (options.realtime)
                keep_pace(network, simulation.seconds(), wall_seconds);
        }
    } catch (const std::exception &error) {
        std::fprintf(stderr, "epuck-emu: %s\n", error.what());
        return aseba::command_line::EXIT_FAILED;
    }
    double wall = wall_seconds();
    std::printf("epuck-emu: stopped at %.1f simulated s after %.1f s (%.2fx real time, %.2f s "
                "of wall clock per simulated second and robot), %llu frames on the network\n",
                simulation.seconds(),
                wall,
                simulation.seconds() / std::max(wall, 1e-9),
                wall / std::max(simulation.seconds() * double(simulation.robot_count()), 1e-9),
                static_cast<unsigned long long>(network.frames_moved()));
    return exit_status(false);
}

// Arena mode: the robots in an Enki world, in simulated time (see
// tools/emulator/arena_simulation.hpp); returns the exit status.
int run_arena(const Options &options,
              const aseba::ProgramFile &program,
              const std::vector<uint16_t> &bytecode)
{
    using aseba::arena::Arena;
    Arena arena;
    try {
        if (options.arena == "default")
            arena = aseba::arena::default_arena(options.robots_given ? options.robots : 6);
        else
            arena = aseba::arena::read_arena_file(options.arena);
        if (options.robots_given)
            aseba::arena::set_robot_count(arena, options.robots);
        if (options.drawn_starts)
            aseba::arena::draw_start_positions(arena, options.seed);
    } catch (const std::exception &error) {
        fail(error.what());
    }
    if (!options.dspic30_image.empty())
        return run_dspic30_arena(options, arena, bytecode);
    std::unique_ptr<aseba::arena::ArenaSimulation> simulation_owner;
    try {
        simulation_owner = std::make_unique<aseba::arena::ArenaSimulation>(
          arena,
          options.seed,
          bytecode,
          memory_preparation(options),
          firmware_threads(options, arena.robots.size()));
    } catch (const std::exception &error) {
        fail(error.what());
    }
    aseba::arena::ArenaSimulation &simulation = *simulation_owner;
    aseba::host::Network &network = simulation.network();
    reserve_descriptors(options, simulation.robot_count());
    open_port([&] {
        network.listen(options.port, options.listen_address);
        listen_robot_ports(options,
                           network,
                           simulation.robot_count(),
                           [&](size_t i) -> hal_board & { return simulation.board(i); });
    });
    std::unique_ptr<aseba::arena::ControlPort> control;
    if (options.control_port != 0)
        open_port([&] {
            control = std::make_unique<aseba::arena::ControlPort>(
              options.control_port, [&simulation](const std::string &line) {
                  return aseba::arena::run_control_command(simulation, line);
              });
        });
    std::unique_ptr<aseba::arena::ArenaFeed> feed;
    if (options.arena_feed != 0)
        open_port([&] {
            feed = std::make_unique<aseba::arena::ArenaFeed>(
              arena, options.listen_address, options.arena_feed);
        });
    aseba::host::NetworkStatus status(program.definitions.events);
    if (!options.quiet) // the status line is the only reader of the counts
        network.observe([&status](aseba::host::FrameView frame) { status.count(frame); });
    MemoryFiles memories(options, simulation.robot_count(), [&](size_t i) -> host_robot & {
        return simulation.robot(i);
    });

    std::printf("epuck-emu: arena %s (%.0f x %.0f cm, %zu ground area%s), %zu robot%s on "
                "tcp:port=%u%s%s, seed %u, %s speed%s%s\n",
                options.arena.c_str(),
                arena.width,
                arena.height,
                arena.areas.size(),
                arena.areas.size() == 1 ? "" : "s",
                arena.robots.size(),
                arena.robots.size() == 1 ? "" : "s",
                unsigned(options.port),
                listen_note(options).c_str(),
                robot_ports_note(options, arena.robots.size()).c_str(),
                unsigned(options.seed),
                options.realtime ? "real-time" : "maximum",
                options.load.empty() ? "" : ", running ",
                options.load.c_str());
    if (control)
        std::printf("epuck-emu: control commands on 127.0.0.1 port %u, one a line (help)\n",
                    unsigned(control->port()));
    flush_output();

    const bool terminal = isatty(STDOUT_FILENO);
    const double status_period = terminal ? 0.5 : 10; // wall-clock seconds
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    const std::clock_t processor_start = std::clock();
    auto wall_seconds = [&] { return std::chrono::duration<double>(clock::now() - start).count(); };
    double next_status = status_period;
    double next_feed = 0;
    double last_status_wall = 0;
    double last_status_simulated = 0;
    while (!stop_requested) {
        if (options.duration_seconds > 0 && simulation.seconds() >= options.duration_seconds)
            break;
        simulation.step();
        memories.sync();
        if (options.realtime)
            keep_pace(network, simulation.seconds(), wall_seconds);
        const double wall = wall_seconds();
        if (control)
            control->service();
        if (feed) {
            if (wall >= next_feed) {
                next_feed = wall + aseba::arena::ArenaFeed::PERIOD_SECONDS;
                feed->publish(simulation.seconds(), feed_robots(simulation));
            }
            feed->service();
        }
        if (!options.quiet && !output_failed && wall >= next_status) {
            next_status = wall + status_period;
            double factor = (simulation.seconds() - last_status_simulated) /
                            std::max(wall - last_status_wall, 1e-9);
            last_status_wall = wall;
            last_status_simulated = simulation.seconds();
            char head[64];
            std::snprintf(head, sizeof head, "%6.1fx real time | ", factor);
            std::string line =
              head +
              status.line(simulation.seconds(), simulation.robot_count(), network.client_count());
            std::printf(terminal ? "\r%s\033[K" : "%s\n", line.c_str());
            flush_output();
        }
    }
    double wall = wall_seconds();
    // Processor time, every thread's: unlike the wall clock, it does not
    // depend on what else the computer runs.
    double processor = double(std::clock() - processor_start) / CLOCKS_PER_SEC;
    std::printf("%sepuck-emu: stopped at %.1f simulated s after %.1f s (%.1fx real time), "
                "%llu frames on the network, %.2f s of processor time on %u thread%s\n",
                terminal && !options.quiet ? "\n" : "",
                simulation.seconds(),
                wall,
                simulation.seconds() / std::max(wall, 1e-9),
                static_cast<unsigned long long>(network.frames_moved()),
                processor,
                simulation.threads(),
                simulation.threads() == 1 ? "" : "s");
    if (!options.quiet) {
        std::string line =
          status.line(simulation.seconds(), simulation.robot_count(), network.client_count());
        std::printf("epuck-emu: %s\n", line.c_str());
    }
    memories.sync();
    return exit_status(memories.failed());
}

} // namespace

int main(int argc, char **argv)
{
    Options options = parse_options(argc, argv);
    std::signal(SIGINT, request_stop);
    std::signal(SIGTERM, request_stop);
    std::signal(SIGPIPE, SIG_IGN);

    std::vector<uint16_t> bytecode;
    aseba::ProgramFile program;
    if (!options.load.empty())
        program = load_program(options, bytecode);
    if (!options.arena.empty())
        return run_arena(options, program, bytecode);

    std::vector<std::unique_ptr<host_robot>> robots;
    aseba::host::Network network;
    reserve_descriptors(options, options.robots);
    open_port([&] { network.listen(options.port, options.listen_address); });
    try {
        auto prepare = memory_preparation(options);
        for (unsigned i = 0; i < options.robots; i++) {
            auto robot = std::make_unique<host_robot>();
            host_robot_init(robot.get(), uint16_t(i + 1), nullptr, nullptr);
            network.attach(&robot->board);
            aseba::host::power_on(*robot, prepare, bytecode);
            robots.push_back(std::move(robot));
        }
    } catch (const std::exception &error) {
        fail(error.what());
    }
    open_port([&] {
        listen_robot_ports(options, network, robots.size(), [&](size_t i) -> hal_board & {
            return robots[i]->board;
        });
    });
    aseba::host::NetworkStatus status(program.definitions.events);
    if (!options.quiet) // the status line is the only reader of the counts
        network.observe([&status](aseba::host::FrameView frame) { status.count(frame); });
    MemoryFiles memories(
      options, robots.size(), [&](size_t i) -> host_robot & { return *robots[i]; });

    std::printf("epuck-emu: %u robot%s on tcp:port=%u%s%s%s%s\n",
                options.robots,
                options.robots == 1 ? "" : "s",
                unsigned(options.port),
                listen_note(options).c_str(),
                robot_ports_note(options, robots.size()).c_str(),
                options.load.empty() ? "" : ", running ",
                options.load.c_str());
    flush_output();

    // The status line rewrites itself on a terminal, and is logged every 10 s
    // elsewhere.
    const bool terminal = isatty(STDOUT_FILENO);
    const double status_period = terminal ? 0.5 : 10;
    double next_status = status_period;

    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    while (!stop_requested) {
        auto elapsed = clock::now() - start;
        double seconds = std::chrono::duration<double>(elapsed).count();
        if (options.duration_seconds > 0 && seconds >= options.duration_seconds)
            break;
        uint32_t now_ms =
          uint32_t(std::chrono::duration_cast<std::chrono::milliseconds>(elapsed).count());
        // Each robot works through what it has (a frame per poll) before the
        // network's next pass, as in the arena: a pass per frame would cost
        // each event a whole round of the sockets.
        bool busy = false;
        for (auto &robot : robots) {
            host_board_set_time(&robot->board, now_ms);
            bool robot_busy = true;
            for (int poll = 0; robot_busy && poll < polls_per_pass; poll++)
                robot_busy = host_robot_poll(robot.get());
            busy |= robot_busy;
        }
        memories.sync();
        // Wait for the network only when no robot has work left; the robots'
        // clocks tick in milliseconds, so never wait longer than one.
        network.service(busy ? 0 : 1);
        if (!options.quiet && !output_failed && seconds >= next_status) {
            next_status += status_period;
            std::string line = status.line(seconds, robots.size(), network.client_count());
            std::printf(terminal ? "\r%s\033[K" : "%s\n", line.c_str());
            flush_output();
        }
    }
    std::printf("%sepuck-emu: stopped after %.1f s, %llu frames on the network\n",
                terminal && !options.quiet ? "\n" : "",
                std::chrono::duration<double>(clock::now() - start).count(),
                static_cast<unsigned long long>(network.frames_moved()));
    memories.sync();
    return exit_status(memories.failed());
}
