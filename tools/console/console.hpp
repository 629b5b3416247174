// What the subcommands of `aseba` share: the parsed command line, the
// connection to the network with its nodes, and where a node's program comes
// from (the --program option or the record of the last `aseba load`).

#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tools/client/flasher.hpp"
#include "tools/client/network.hpp"

namespace aseba::console
{

using client::Milliseconds;
using client::NodeKey;

// Bad usage of the command line: exit status 2 and a hint to --help.
class UsageError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// An input file that cannot be read or used (a program, an image): exit
// status 2, as for bad usage, without the hint.
class InputError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// The exit statuses of every program (tools/command_line/command_line.hpp).
constexpr int EXIT_FAILED = 1;
constexpr int EXIT_USAGE = 2;

struct Options {
    std::string command;
    std::vector<std::string> arguments; // after the command
    std::vector<std::string> targets;
    std::vector<std::string> node_selectors; // empty: every node
    Milliseconds timeout = client::DEFAULT_ANSWER_TIMEOUT;
    std::string program_file;               // --program
    CommonDefinitions declared;             // --event NAME[:SIZE] for scripts
    std::vector<std::string> event_filters; // monitor --event
    std::optional<unsigned long> count;     // watch, monitor, break wait
    std::optional<double> duration_seconds; // monitor, break wait
    Milliseconds interval{ 200 };           // watch
    bool describe = false;                  // nodes
    bool listing = false;                   // compile
    bool paused = false;                    // load: leave the program reset, not running
    bool wait = false;                      // break set: wait for hits
    bool by_line = false;                   // step: up to the next source line
    bool all_messages = false;              // monitor: also descriptions, variables, ...
    bool no_reboot = false;                 // flash: the nodes already wait in their bootloaders
};

// Parses argv; throws UsageError. `--help` and `help` set command "help".
Options parse_command_line(int argc, char **argv);

// The text of `aseba --help` or of `aseba help COMMAND` (throws UsageError
// for an unknown command).
std::string help_text(const std::string &command = {});

// A connected network with the nodes that answered discovery.
class Session
{
  public:
    explicit Session(const Options &options);

    client::Network &network()
    {
        return network_;
    }
    const Options &options() const
    {
        return options_;
    }

    // The nodes the --node options select (all nodes when none is given).
    std::vector<NodeKey> selected_nodes() const;

    // Gives each selected node its program: the --program file, else the
    // one recorded by the last `aseba load` of that node. Compile errors
    // throw; a node without a program is left without.
    void attach_programs(const std::vector<NodeKey> &nodes);

    // Records that `file` (with `declared` events) was loaded on `key`, so
    // that later commands know its variables, events and lines; false after
    // saying on standard error that the record could not be written.
    bool record_load(NodeKey key, const std::string &file);

    // The global events known for `key` (its program's, else --event ones).
    const CommonDefinitions &definitions_for(NodeKey key) const;

    // A label for messages: "e-puck 1" (plus the target when several).
    std::string label(NodeKey key) const;

  private:
    Options options_;
    client::Network network_;
};

// The subcommands; each returns the exit status.
int command_nodes(Session &session);
int command_compile(Session &session);
int command_load(Session &session);
int command_execution(Session &session); // run, pause, step, stop, reset
int command_break(Session &session);
int command_vars(Session &session);
int command_watch(Session &session);
int command_emit(Session &session);
int command_monitor(Session &session);
int command_save(Session &session);
int command_reboot(Session &session);
int command_flash(Session &session);

// The pages of a Microchip HEX application image for `aseba flash`, checked
// whole as the robots' bootloaders will check it (records, descriptor, CRC),
// so that no robot is taken out of service for an image it would refuse.
// Throws InputError.
std::vector<client::FlashPage> read_flash_image(const std::string &path);

// True once Ctrl-C was pressed (watch and monitor stop then).
bool interrupted();

// Installs the Ctrl-C handler that sets interrupted().
void catch_interrupt();

} // namespace aseba::console
