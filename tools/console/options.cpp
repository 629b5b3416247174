// The command line of `aseba` (CLI11): its commands with their help, its
// options, and the Options they fill. Apart from main.cpp so that a fuzz
// target can run it (tests/fuzz/command_line_fuzzer.cpp).

#include <cstdlib>
#include <map>

#include "console.hpp"
#include "tools/command_line/command_line.hpp"

namespace aseba::console
{

namespace
{

const char *const OVERVIEW =
  R"(The console of Aseba networks: list, program, debug and watch a group of
robots (protocol 5) from one PC. `aseba help COMMAND` (or `aseba COMMAND
--help`) tells the details of a command; the options below work with every
command, before or after it.)";

// One subcommand: its name, a line for the list, its usage lines and what it
// does.
struct CommandText {
    const char *name;
    const char *summary;
    const char *usage;
    const char *details;
};

const CommandText COMMANDS[] = {
    { "nodes",
      "list the nodes and their descriptions",
      "usage: aseba nodes [--describe]",
      R"(Lists the nodes that answer on the targets: id, name, protocol version, memory
sizes and execution state. With --describe (-d), also their named variables,
local events and native functions.)" },
    { "compile",
      "compile a script or .aesl project against the live nodes",
      "usage: aseba compile FILE [--listing]",
      R"(Compiles FILE (a script, or an .aesl project) for each selected node with the
description that node sends, and reports the sizes. Errors are printed as
FILE:LINE:COLUMN with the line and a caret. --listing prints the bytecode with
source lines.)" },
    { "load",
      "compile, upload and run a program on the selected nodes",
      "usage: aseba load FILE [--node NODE]... [--paused]",
      R"(Compiles FILE for each selected node (default: all), uploads the bytecode in
chunks of 256 words and runs it. For an .aesl project each node gets the
program of its id and name, else of its name, else the project's only
program. --paused leaves the program reset, stopped at its start (for step).
The load is recorded so that later commands know the program's variables,
events and lines.)" },
    { "run",
      "run the selected nodes (also: pause, step, stop, reset)",
      "usage: aseba run [--node NODE]...",
      "Runs the selected nodes; a node stopped on a breakpoint steps past it first." },
    { "pause",
      "pause the selected nodes",
      "usage: aseba pause [--node NODE]...",
      "Pauses the selected nodes (step-by-step mode) and prints where they are." },
    { "step",
      "execute one instruction, or one line",
      "usage: aseba step [--line] [--node NODE]...",
      R"(Executes one instruction on each selected node that is inside an event, and
prints the new position with its source line. With --line, steps until the
node reaches another source line (Aseba Studio's Next; needs the program).)" },
    { "stop",
      "stop the selected nodes",
      "usage: aseba stop [--node NODE]...",
      "Stops the selected nodes: the current event is abandoned." },
    { "reset",
      "reset the selected nodes",
      "usage: aseba reset [--node NODE]...",
      "Resets the selected nodes: stopped, with the init code about to run." },
    { "break",
      "breakpoints by source line, and their hits",
      R"(usage: aseba break set LINE [--node NODE]... [--wait]
       aseba break clear LINE|all [--node NODE]...
       aseba break wait [--count N] [--duration S])",
      R"(Sets or clears a breakpoint at the first instruction of source line LINE of
the node's program (--program or the last load). `break set --wait` and
`break wait` then report each node that stops, with the source line, until N
hits (default 1) or S seconds (default: the timeout).)" },
    { "vars",
      "read or write variables by name",
      R"(usage: aseba vars [NAME | NAME[i] | NAME[i:j]]... [NAME=V[,V...]]...
       aseba vars NAME = V [V...])",
      R"(Reads variables by name (all of them when no name is given) or writes them
(one value fills the whole variable or slice). Slices are inclusive, as in the
Aseba language: camR[0:9] is 10 words. User variables are known from the
program (--program, or the last load).)" },
    { "watch",
      "live table of variables of the selected nodes",
      "usage: aseba watch NAME... [--interval MS] [--count N]",
      R"(Reads the variables of every selected node again and again and shows them as
a table (one row per node), until Ctrl-C or N refreshes.)" },
    { "emit",
      "send a global event to the network",
      "usage: aseba emit EVENT [ARGS...]",
      R"(Sends a global event from the host to every target. EVENT is a name of the
program's global events (or declared with --event NAME:SIZE), or a number.)" },
    { "monitor",
      "print every event and error on the network",
      R"(usage: aseba monitor [--node NODE]... [--event NAME]... [--duration S]
                     [--count N] [--all])",
      R"(Prints every event and error on the network with its time (UTC), sender and
decoded content; event names and source lines come from the nodes' programs.
--node keeps messages from these nodes, --event keeps these events only, --all
also shows descriptions, variables and other debugger traffic. Stops after S
seconds, N messages, or Ctrl-C.)" },
    { "save",
      "write the node's bytecode to its storage",
      "usage: aseba save [FILE] [--node NODE]...",
      R"(Asks the selected nodes to write their current bytecode to their storage
(WRITE_BYTECODE), so that it runs at the next boot. With FILE, the program is
first compiled and uploaded (like load). Nodes do not have to confirm.)" },
    { "reboot",
      "reboot the selected nodes",
      "usage: aseba reboot [--node NODE]...",
      "Reboots the selected nodes (REBOOT; no answer is expected)." },
    { "flash",
      "write a firmware image into the selected robots at once",
      "usage: aseba flash IMAGE.hex [--node NODE]... [--no-reboot]",
      R"(Writes a firmware image (Microchip Intel HEX with the application descriptor,
as `make dspic30` writes build/dspic30/epuck-aseba.hex) into every selected
robot at once (default: all), through their Aseba bootloaders (protocol 5's bootloader messages,
bootloader/README.md). The whole image is checked first (records that overlap, the
descriptor and its CRC): a robot is never rebooted for an image its
bootloader would refuse. Each robot is sent REBOOT, its bootloader describes
itself, every page is written and acknowledged, then BOOTLOADER_RESET starts
the new image and the robot must answer as a node again. Robots progress
independently; a page whose acknowledgement is lost is sent again (3
attempts). A progress bar is shown on a terminal, then one line per robot. A
robot whose image is invalid waits in its bootloader and does not answer as
a node: name it by id with --node ID to flash it anyway. --no-reboot sends
no REBOOT and waits up to 10 s (or --timeout) for each robot's bootloader to
describe itself: start the command, then switch the robots on or reset
them. An interrupted flashing leaves the robot in its bootloader, which
waits for a new one. Exit status 1 when any robot failed.)" },
    { "help",
      "the options and details of a command",
      "usage: aseba help [COMMAND]",
      "Shows the help of COMMAND, or of aseba." },
};

// Milliseconds, seconds and counts: not negative (the type name says which).
CLI::Validator non_negative()
{
    return CLI::Range(0.0, 1e9).description("");
}

// The parser of the whole command line, filling `options`.
struct CommandLine {
    CLI::App app{ OVERVIEW, "aseba" };
    std::map<std::string, CLI::App *> commands;
    std::vector<std::string> event_declarations;
    unsigned long timeout_ms = 0;
    unsigned long count = 0;
    double duration_seconds = 0;
    unsigned long interval_ms = 0;

    explicit CommandLine(Options &options)
    {
        auto formatter = command_line::use_common_style(app);
        formatter->set_usage(&app, "usage: aseba [options] COMMAND [ARGS]");
        app.footer(command_line::EXIT_STATUS_TEXT);
        // Options of every command are taken after the command too.
        app.fallthrough();
        app.require_subcommand(0, 1);
        app
          .add_option("-t,--target",
                      options.targets,
                      "a network to connect to, repeatable: tcp:HOST;PORT, HOST:PORT,\n"
                      "ser:device=PATH or a device path (115200 8N1) (default\n"
                      "tcp:localhost;33333)")
          ->allow_extra_args(false)
          ->type_name("TARGET");
        app
          .add_option("-n,--node",
                      options.node_selectors,
                      "the nodes to act on: an id, a name, or all (default all);\n"
                      "repeatable")
          ->allow_extra_args(false)
          ->type_name("NODE");
        app.add_option("--timeout", timeout_ms, "how long to wait for any answer (default 1000)")
          ->check(non_negative())
          ->type_name("MS");
        app
          .add_option("-p,--program",
                      options.program_file,
                      "the program on the nodes (for variable names, events and source\n"
                      "lines); default: the one the last `aseba load` put there")
          ->type_name("FILE");
        app
          .add_option("--event",
                      event_declarations,
                      "declare a global event of SIZE words for bare scripts;\n"
                      "repeatable (an .aesl project declares its own)")
          ->allow_extra_args(false)
          ->type_name("NAME[:SIZE]");

        for (const CommandText &text : COMMANDS) {
            CLI::App *command = app.add_subcommand(text.name, text.summary);
            formatter->set_usage(command, text.usage, text.details);
            command->footer("The options of every command: aseba --help.");
            commands[text.name] = command;
        }
        add_arguments(options);
        add_command_options(options);
    }

    void add_arguments(Options &options)
    {
        struct Arguments {
            const char *command;
            const char *name;
            const char *meaning;
            bool exactly_one;
        };
        const Arguments arguments[] = {
            { "compile", "FILE", "a script, or an .aesl project", true },
            { "load", "FILE", "a script, or an .aesl project", true },
            { "break", "ACTION", "set LINE, clear LINE|all, or wait", false },
            { "vars", "VARIABLE", "NAME, NAME[i], NAME[i:j] or NAME=V[,V...]", false },
            { "watch", "NAME", "the variables to watch", false },
            { "emit", "EVENT", "the event's name or number, then its arguments", false },
            { "save", "FILE", "a program to load first", false },
            { "flash", "IMAGE.hex", "the application image", true },
            { "help", "COMMAND", "the command to explain", false },
        };
        for (const Arguments &argument : arguments) {
            CLI::Option *option = commands[argument.command]->add_option(
              argument.name, options.arguments, argument.meaning);
            option->type_name("");
            if (argument.exactly_one)
                option->expected(1)->required();
        }
    }

    void add_command_options(Options &options)
    {
        commands["nodes"]->add_flag(
          "-d,--describe", options.describe, "also the named variables, local events and natives");
        commands["compile"]->add_flag(
          "--listing", options.listing, "print the bytecode with source lines");
        commands["load"]->add_flag(
          "--paused", options.paused, "leave the program reset, stopped at its start");
        commands["step"]->add_flag("--line", options.by_line, "step up to the next source line");
        commands["break"]->add_flag("--wait", options.wait, "wait for the hits after `break set`");
        commands["monitor"]->add_flag(
          "--all", options.all_messages, "also descriptions, variables and other debugger traffic");
        commands["monitor"]
          ->add_option("--event", options.event_filters, "show only this event; repeatable")
          ->allow_extra_args(false)
          ->type_name("NAME");
        commands["flash"]->add_flag(
          "--no-reboot", options.no_reboot, "the robots wait in their bootloaders already");
        for (const char *name : { "watch", "monitor", "break" })
            commands[name]
              ->add_option("--count", count, "stop after N refreshes, messages or hits")
              ->check(non_negative())
              ->type_name("N");
        for (const char *name : { "monitor", "break" })
            commands[name]
              ->add_option("--duration", duration_seconds, "stop after S seconds")
              ->check(non_negative())
              ->type_name("S");
        commands["watch"]
          ->add_option("--interval", interval_ms, "time between refreshes (default 200)")
          ->check(non_negative())
          ->type_name("MS");
    }

    // What only the parse can tell, moved into `options`.
    void finish(Options &options)
    {
        for (const auto &[name, command] : commands)
            if (command->parsed())
                options.command = name;
        if (app.get_option("--timeout")->count() > 0)
            options.timeout = Milliseconds(timeout_ms);
        if (any_parsed("--count"))
            options.count = count;
        if (any_parsed("--duration"))
            options.duration_seconds = duration_seconds;
        if (commands["watch"]->get_option("--interval")->count() > 0)
            options.interval = Milliseconds(interval_ms);
        try {
            for (const std::string &text : event_declarations)
                options.declared.events.push_back(parse_event_declaration(text));
        } catch (const std::invalid_argument &error) {
            throw UsageError(error.what());
        }
    }

    bool any_parsed(const std::string &option) const
    {
        for (const auto &[name, command] : commands) {
            const CLI::Option *found = command->get_option_no_throw(option);
            if (found != nullptr && found->count() > 0)
                return true;
        }
        return false;
    }
};

} // namespace

std::string help_text(const std::string &command)
{
    Options ignored;
    CommandLine parser(ignored);
    if (command.empty())
        return parser.app.help();
    auto found = parser.commands.find(command);
    if (found == parser.commands.end())
        throw UsageError("no command '" + command + "'");
    return found->second->help("aseba");
}

Options parse_command_line(int argc, char **argv)
{
    Options options;
    CommandLine parser(options);
    try {
        parser.app.parse(argc, argv);
    } catch (const CLI::CallForHelp &) {
        // `aseba CMD --help` is `aseba help CMD`.
        Options help;
        help.command = "help";
        for (const auto &[name, command] : parser.commands)
            if (command->parsed() && name != "help")
                help.arguments = { name };
        return help;
    } catch (const CLI::ExtrasError &error) {
        std::vector<std::string> extra = parser.app.remaining();
        if (parser.app.get_subcommands().empty() && !extra.empty())
            throw UsageError(extra.front().rfind('-', 0) == 0
                               ? "unknown option '" + extra.front() + "'"
                               : "no command '" + extra.front() + "'");
        throw UsageError(error.what());
    } catch (const CLI::ParseError &error) {
        throw UsageError(error.what());
    }
    parser.finish(options);
    if (options.targets.empty())
        options.targets.push_back(client::DEFAULT_TARGET);
    return options;
}

} // namespace aseba::console
