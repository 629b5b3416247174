// The arena's control commands (see arena_control.hpp).

#include "arena_control.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace aseba::arena
{
namespace
{

const char help_text[] = "ok commands: selector ROBOT POSITION (0..15) | rc5 ROBOT COMMAND "
                         "(0..63) [ADDRESS (0..31, default 0)] | status | help; ROBOT is a "
                         "node id or all";

constexpr unsigned selector_highest = 15;
constexpr unsigned rc5_command_highest = 63;
constexpr unsigned rc5_address_highest = 31;

// A command's mistake, reported as "error: ...".
struct CommandError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

unsigned whole_number(const std::string &text, const char *what, unsigned highest)
{
    size_t used = 0;
    unsigned long value = 0;
    try {
        value = std::stoul(text, &used);
    } catch (const std::exception &) {
        used = 0;
    }
    if (used == 0 || used != text.size() || text[0] == '-' || value > highest)
        throw CommandError(std::string(what) + " is a whole number from 0 to " +
                           std::to_string(highest) + ", not '" + text + "'");
    return unsigned(value);
}

// The robots `target` names: every robot, or those answering to a node id.
std::vector<size_t> robots_named(ArenaSimulation &simulation, const std::string &target)
{
    std::vector<size_t> robots;
    if (target == "all") {
        for (size_t i = 0; i < simulation.robot_count(); i++)
            robots.push_back(i);
        return robots;
    }
    unsigned id = whole_number(target, "ROBOT (a node id, or all)", 0xFFFF);
    for (size_t i = 0; i < simulation.robot_count(); i++)
        if (simulation.node_id(i) == id)
            robots.push_back(i);
    if (robots.empty())
        throw CommandError("no robot answers to node id " + target);
    return robots;
}

std::string robots_text(ArenaSimulation &simulation, const std::vector<size_t> &robots)
{
    if (robots.size() == simulation.robot_count() && robots.size() > 1)
        return "every robot";
    std::string text = robots.size() == 1 ? "robot " : "robots ";
    for (size_t i = 0; i < robots.size(); i++)
        text += (i > 0 ? ", " : "") + std::to_string(simulation.node_id(robots[i]));
    return text;
}

std::string status_text(ArenaSimulation &simulation)
{
    char head[64];
    std::snprintf(head, sizeof head, "ok time %.2f s", simulation.seconds());
    std::string text = head;
    for (size_t i = 0; i < simulation.robot_count(); i++) {
        const Battery &battery = simulation.world().battery(i);
        char robot[128];
        std::snprintf(robot,
                      sizeof robot,
                      "; robot %u: selector %u, battery %.3f V (%.1f %%%s)",
                      unsigned(simulation.node_id(i)),
                      unsigned(simulation.world().selector(i)),
                      battery.volts(),
                      battery.charge() * 100,
                      battery.low() ? ", low" : "");
        text += robot;
    }
    return text;
}

std::string run(ArenaSimulation &simulation, const std::vector<std::string> &words)
{
    const std::string &command = words[0];
    if (command == "help" && words.size() == 1)
        return help_text;
    if (command == "status" && words.size() == 1)
        return status_text(simulation);
    if (command == "selector" && words.size() == 3) {
        std::vector<size_t> robots = robots_named(simulation, words[1]);
        unsigned position = whole_number(words[2], "POSITION", selector_highest);
        for (size_t robot : robots)
            simulation.set_selector(robot, uint16_t(position));
        return "ok selector of " + robots_text(simulation, robots) + " at " +
               std::to_string(position);
    }
    if (command == "rc5" && (words.size() == 3 || words.size() == 4)) {
        std::vector<size_t> robots = robots_named(simulation, words[1]);
        unsigned code = whole_number(words[2], "COMMAND", rc5_command_highest);
        unsigned address =
          words.size() == 4 ? whole_number(words[3], "ADDRESS", rc5_address_highest) : 0;
        simulation.press_remote_key(robots, uint8_t(address), uint8_t(code));
        return "ok rc5 command " + std::to_string(code) + " (address " + std::to_string(address) +
               ") to " + robots_text(simulation, robots);
    }
    throw CommandError("unknown command or wrong number of words: '" + command + "' (try help)");
}

} // namespace

std::string run_control_command(ArenaSimulation &simulation, const std::string &line)
{
    std::istringstream stream(line);
    std::vector<std::string> words;
    for (std::string word; stream >> word;)
        words.push_back(word);
    if (words.empty())
        return "error: empty command (try help)";
    try {
        return run(simulation, words);
    } catch (const CommandError &error) {
        return std::string("error: ") + error.what();
    }
}

} // namespace aseba::arena
