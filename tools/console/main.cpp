// aseba: the console for a group of Aseba robots. Git-style subcommands over
// the client library; this file dispatches the command line that options.cpp
// reads.

#include <csignal>
#include <cstdlib>
#include <iostream>
#include <map>

#include "console.hpp"
#include "tools/client/terminal_text.hpp"
#include "tools/command_line/command_line.hpp"

namespace aseba::console
{

namespace
{

volatile std::sig_atomic_t interrupt_flag = 0;

void on_interrupt(int)
{
    interrupt_flag = 1;
}

// Reads the command's input files before any network is touched: a file
// that cannot be used is bad usage (status 2), whatever the network does.
// What the command line names, checked before any connection: a target
// that is no target at all is bad usage, as a missing file is.
void check_input_files(const Options &options)
{
    for (const std::string &target : options.targets)
        try {
            client::parse_target(target);
        } catch (const client::TransportError &error) {
            throw UsageError(error.what());
        }
    const std::string &command = options.command;
    bool program_argument = command == "load" || command == "compile" || command == "save";
    if (program_argument && !options.arguments.empty())
        client::read_program_file(options.arguments[0], options.declared);
    if (!options.program_file.empty())
        client::read_program_file(options.program_file, options.declared);
    if (command == "flash" && !options.arguments.empty())
        read_flash_image(options.arguments[0]);
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

} // namespace aseba::console

namespace
{

// The program; its output is checked by main.
int run_command(int argc, char **argv)
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
        check_input_files(options);
        catch_interrupt();
        Session session(options);
        return command->second(session);
    } catch (const UsageError &error) {
        std::cerr << "aseba: " << error.what() << "\n(aseba --help for usage)\n";
        return EXIT_USAGE;
    } catch (const InputError &error) {
        std::cerr << "aseba: " << error.what() << "\n";
        return EXIT_USAGE;
    } catch (const aseba::client::FileError &error) {
        std::cerr << "aseba: " << error.what() << "\n";
        return EXIT_USAGE;
    } catch (const std::exception &error) {
        std::cerr << "aseba: " << error.what() << "\n";
        return EXIT_FAILED;
    }
}

} // namespace

int main(int argc, char **argv)
{
    // Names and messages come from the network: escaped before any
    // terminal sees them, whichever command prints them.
    aseba::client::TerminalFilter output(std::cout), errors(std::cerr);
    return aseba::command_line::finish_standard_output("aseba", run_command(argc, argv));
}
