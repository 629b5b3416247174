// aseba: the console for a group of Aseba robots. Git-style subcommands over
// the client library; this file reads the command line and dispatches.

#include <csignal>
#include <cstdlib>
#include <iostream>
#include <map>

#include "console.hpp"

namespace aseba::console
{

namespace
{

const char *const OVERVIEW = R"(usage: aseba [options] COMMAND [ARGS]

The console of Aseba networks: list, program, debug and watch a group of
robots (protocol 5) from one PC.

Commands:
  nodes              list the nodes and their descriptions
  compile FILE       compile a script or .aesl project against the live nodes
  load FILE          compile, upload and run a program on the selected nodes
  run|pause|step|stop|reset
                     control the execution of the selected nodes
  break set|clear LINE, break wait
                     breakpoints by source line, and their hits
  vars [NAME[i:j]...] [NAME=VALUES]
                     read or write variables by name
  watch NAME...      live table of variables of the selected nodes
  emit EVENT [ARGS]  send a global event to the network
  monitor            print every event and error on the network
  save [FILE]        write the node's bytecode to its storage (WRITE_BYTECODE)
  reboot             reboot the selected nodes
  flash IMAGE.hex    write a firmware image into the selected robots at once,
                     through their bootloaders
  help COMMAND       the options and details of a command

Options for every command:
  -t, --target TARGET  a network to connect to, repeatable: tcp:HOST;PORT,
                       HOST:PORT, ser:device=PATH or a device path (115200 8N1)
                       (default tcp:localhost;33333)
  -n, --node NODE      the nodes to act on: an id, a name, or all (default all);
                       repeatable
  --timeout MS         how long to wait for any answer (default 1000)
  -p, --program FILE   the program on the nodes (for variable names, events and
                       source lines); default: the one the last `aseba load`
                       put there
  --event NAME[:SIZE]  declare a global event of SIZE words for bare scripts;
                       repeatable (an .aesl project declares its own)
  -h, --help           this text

Exit status: 0 on success, 1 when the network, a node or the compiler reports
a failure, 2 on bad usage.
)";

const std::map<std::string, std::string> COMMAND_HELP = {
    { "nodes", R"(usage: aseba nodes [--describe]

Lists the nodes that answer on the targets: id, name, protocol version, memory
sizes and execution state. With --describe (-d), also their named variables,
local events and native functions.
)" },
    { "compile", R"(usage: aseba compile FILE [--listing]

Compiles FILE (a script, or an .aesl project) for each selected node with the
description that node sends, and reports the sizes. Errors are printed as
FILE:LINE:COLUMN with the line and a caret. --listing prints the bytecode with
source lines.
)" },
    { "load", R"(usage: aseba load FILE [--node NODE]... [--paused]

Compiles FILE for each selected node (default: all), uploads the bytecode in
chunks of 256 words and runs it. For an .aesl project each node gets the
program of its id and name, else of its name, else the project's only
program. --paused leaves the program reset, stopped at its start (for step).
The load is recorded so that later commands know the program's variables,
events and lines.
)" },
    { "run", R"(usage: aseba run [--node NODE]...

Runs the selected nodes; a node stopped on a breakpoint steps past it first.
)" },
    { "pause", R"(usage: aseba pause [--node NODE]...

Pauses the selected nodes (step-by-step mode) and prints where they are.
)" },
    { "step", R"(usage: aseba step [--line] [--node NODE]...

Executes one instruction on each selected node that is inside an event, and
prints the new position with its source line. With --line, steps until the
node reaches another source line (Aseba Studio's Next; needs the program).
)" },
    { "stop", R"(usage: aseba stop [--node NODE]...

Stops the selected nodes: the current event is abandoned.
)" },
    { "reset", R"(usage: aseba reset [--node NODE]...

Resets the selected nodes: stopped, with the init code about to run.
)" },
    { "break", R"(usage: aseba break set LINE [--node NODE]... [--wait]
       aseba break clear LINE|all [--node NODE]...
       aseba break wait [--count N] [--duration S]

Sets or clears a breakpoint at the first instruction of source line LINE of
the node's program (--program or the last load). `break set --wait` and
`break wait` then report each node that stops, with the source line, until N
hits (default 1) or S seconds (default: the timeout).
)" },
    { "vars", R"(usage: aseba vars [NAME | NAME[i] | NAME[i:j]]... [NAME=V[,V...]]...
       aseba vars NAME = V [V...]

Reads variables by name (all of them when no name is given) or writes them
(one value fills the whole variable or slice). Slices are inclusive, as in the
Aseba language: camR[0:9] is 10 words. User variables are known from the
program (--program, or the last load).
)" },
    { "watch", R"(usage: aseba watch NAME... [--interval MS] [--count N]

Reads the variables of every selected node again and again and shows them as
a table (one row per node), until Ctrl-C or N refreshes.
)" },
    { "emit", R"(usage: aseba emit EVENT [ARGS...]

Sends a global event from the host to every target. EVENT is a name of the
program's global events (or declared with --event NAME:SIZE), or a number.
)" },
    { "monitor", R"(usage: aseba monitor [--node NODE]... [--event NAME]... [--duration S]
                     [--count N] [--all]

Prints every event and error on the network with its time (UTC), sender and
decoded content; event names and source lines come from the nodes' programs.
--node keeps messages from these nodes, --event keeps these events only, --all
also shows descriptions, variables and other debugger traffic. Stops after S
seconds, N messages, or Ctrl-C.
)" },
    { "save", R"(usage: aseba save [FILE] [--node NODE]...

Asks the selected nodes to write their current bytecode to their storage
(WRITE_BYTECODE), so that it runs at the next boot. With FILE, the program is
first compiled and uploaded (like load). Nodes do not have to confirm.
)" },
    { "reboot", R"(usage: aseba reboot [--node NODE]...

Reboots the selected nodes (REBOOT; no answer is expected).
)" },
    { "flash", R"(usage: aseba flash IMAGE.hex [--node NODE]... [--no-reboot]

Writes a firmware image (Microchip Intel HEX with the application descriptor,
as `make dspic30` writes build/dspic30/epuck-aseba.hex) into every selected
robot at once (default: all), through their Aseba bootloaders (protocol.md
§6.9): each robot is sent REBOOT, its bootloader describes itself, every page
is written and acknowledged, then BOOTLOADER_RESET starts the new image and
the robot must answer as a node again. Robots progress independently; a page
whose acknowledgement is lost is sent again (3 attempts). A progress bar is
shown on a terminal, then one line per robot. A robot whose image is invalid
waits in its bootloader and does not answer as a node: name it by id with
--node ID to flash it anyway. --no-reboot sends no REBOOT and waits up to
10 s (or --timeout) for each robot's bootloader to describe itself: start
the command, then switch the robots on or reset them. An interrupted
flashing leaves the robot in its bootloader, which waits for a new one.
Exit status 1 when any robot failed.
)" },
};

volatile std::sig_atomic_t interrupt_flag = 0;

void on_interrupt(int)
{
    interrupt_flag = 1;
}

bool is_number(const std::string &text)
{
    if (text.size() < 2 || text[0] != '-')
        return false;
    return text.find_first_not_of("0123456789,", 1) == std::string::npos;
}

unsigned long parse_count(const std::string &option, const std::string &text)
{
    char *end = nullptr;
    unsigned long value = std::strtoul(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || text[0] == '-')
        throw UsageError(option + " expects a whole number, not '" + text + "'");
    return value;
}

double parse_seconds(const std::string &option, const std::string &text)
{
    char *end = nullptr;
    double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || value < 0)
        throw UsageError(option + " expects a number of seconds, not '" + text + "'");
    return value;
}

GlobalEvent parse_event_declaration(const std::string &text)
{
    GlobalEvent event;
    size_t colon = text.find(':');
    event.name = text.substr(0, colon);
    if (event.name.empty())
        throw UsageError("--event expects NAME[:SIZE], not '" + text + "'");
    if (colon != std::string::npos)
        event.size = uint16_t(parse_count("--event", text.substr(colon + 1)));
    return event;
}

} // namespace

bool interrupted()
{
    return interrupt_flag != 0;
}

void catch_interrupt()
{
    struct sigaction action {
    };
    action.sa_handler = on_interrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0; // no SA_RESTART: a waiting poll() returns at once
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

std::string help_text(const std::string &command)
{
    if (command.empty())
        return OVERVIEW;
    std::string name = command;
    if (auto found = COMMAND_HELP.find(name); found != COMMAND_HELP.end())
        return found->second;
    throw UsageError("no command '" + command + "'");
}

Options parse_command_line(int argc, char **argv)
{
    Options options;
    bool wants_help = false;
    for (int i = 1; i < argc; i++) {
        std::string argument = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc)
                throw UsageError(argument + " needs a value");
            return argv[++i];
        };
        bool option = argument.size() > 1 && argument[0] == '-' && !is_number(argument);
        if (!option) {
            if (options.command.empty())
                options.command = argument;
            else
                options.arguments.push_back(argument);
        } else if (argument == "-h" || argument == "--help") {
            wants_help = true;
        } else if (argument == "-t" || argument == "--target") {
            options.targets.push_back(value());
        } else if (argument == "-n" || argument == "--node") {
            options.node_selectors.push_back(value());
        } else if (argument == "--timeout") {
            options.timeout = Milliseconds(parse_count(argument, value()));
        } else if (argument == "-p" || argument == "--program") {
            options.program_file = value();
        } else if (argument == "--event") {
            std::string text = value();
            if (options.command == "monitor")
                options.event_filters.push_back(text);
            else
                options.declared.events.push_back(parse_event_declaration(text));
        } else if (argument == "--count") {
            options.count = parse_count(argument, value());
        } else if (argument == "--duration") {
            options.duration_seconds = parse_seconds(argument, value());
        } else if (argument == "--interval") {
            options.interval = Milliseconds(parse_count(argument, value()));
        } else if (argument == "-d" || argument == "--describe") {
            options.describe = true;
        } else if (argument == "--listing") {
            options.listing = true;
        } else if (argument == "--paused") {
            options.paused = true;
        } else if (argument == "--wait") {
            options.wait = true;
        } else if (argument == "--line") {
            options.by_line = true;
        } else if (argument == "--all") {
            options.all_messages = true;
        } else if (argument == "--no-reboot") {
            options.no_reboot = true;
        } else {
            throw UsageError("unknown option '" + argument + "'");
        }
    }
    if (wants_help) {
        // `aseba CMD --help` is `aseba help CMD`.
        if (!options.command.empty() && options.command != "help")
            options.arguments.insert(options.arguments.begin(), options.command);
        options.command = "help";
    }
    if (options.targets.empty())
        options.targets.push_back(client::DEFAULT_TARGET);
    return options;
}

} // namespace aseba::console

int main(int argc, char **argv)
{
    using namespace aseba::console;
    using Command = int (*)(Session &);
    const std::map<std::string, Command> commands = {
        { "nodes", command_nodes },     { "compile", command_compile },
        { "load", command_load },       { "run", command_execution },
        { "pause", command_execution }, { "step", command_execution },
        { "stop", command_execution },  { "reset", command_execution },
        { "break", command_break },     { "vars", command_vars },
        { "watch", command_watch },     { "emit", command_emit },
        { "monitor", command_monitor }, { "save", command_save },
        { "reboot", command_reboot },   { "flash", command_flash },
    };
    try {
        Options options = parse_command_line(argc, argv);
        if (options.command.empty() || options.command == "help") {
            std::cout << help_text(options.arguments.empty() ? "" : options.arguments[0]);
            return options.command.empty() && options.arguments.empty() ? EXIT_USAGE : 0;
        }
        auto command = commands.find(options.command);
        if (command == commands.end())
            throw UsageError("no command '" + options.command + "'");
        catch_interrupt();
        Session session(options);
        return command->second(session);
    } catch (const UsageError &error) {
        std::cerr << "aseba: " << error.what() << "\n(aseba --help for usage)\n";
        return EXIT_USAGE;
    } catch (const std::exception &error) {
        std::cerr << "aseba: " << error.what() << "\n";
        return EXIT_FAILED;
    }
}
