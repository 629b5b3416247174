// asebac: the Aseba compiler on the command line, and `asebac run` to try a
// script on the host VM.

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "run.hpp"
#include "tools/command_line/command_line.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/disassembler.hpp"
#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_json.hpp"
#include "tools/compiler/target_presets.hpp"

namespace
{

using namespace aseba;

constexpr unsigned long DEFAULT_STEP_BUDGET = 10000;
constexpr int EXIT_USAGE = command_line::EXIT_USAGE;

const char *const USAGE =
  R"(usage: asebac [options] FILE        compile FILE (a script or an .aesl project; - for stdin)
       asebac run [options] FILE    compile FILE and run it on the host VM)";

const char *const DESCRIPTION =
  R"(With no output option, asebac only checks the program and says how big it
is. Compile errors are printed as file:line:column with the line and a caret.
An .aesl project declares its own events and constants; --event and
--constant declare them for scripts.)";

const char *const RUN_DESCRIPTION =
  R"(Compiles FILE, runs its init code and then each --event on the host VM, and
prints a JSON report: every named and user variable, the events the program
emitted, run-time errors and unfinished events. After a run-time error the
following events still run. With run, --event NAME[:a,b,...] sends the event
with these arguments after init (repeatable, in order); a global event not
declared otherwise is declared with the number of arguments given.)";

struct Options {
    bool run = false;
    std::string input;
    std::string target = "epuck";
    std::string node;
    std::vector<std::string> event_options;
    std::vector<std::string> constant_options;
    std::string output;
    std::string format = "hex";
    bool listing = false;
    bool variables = false;
    unsigned long steps = DEFAULT_STEP_BUDGET;
};

[[noreturn]] void usage_error(const std::string &message)
{
    command_line::print_usage_error("asebac", message);
    std::exit(EXIT_USAGE);
}

std::optional<long> parse_integer(const std::string &text)
{
    if (text.empty())
        return std::nullopt;
    char *end = nullptr;
    long value = std::strtol(text.c_str(), &end, 0);
    if (*end != '\0')
        return std::nullopt;
    return value;
}

// The options of both forms; those given before `run` reach it too.
void add_common_options(CLI::App &app, Options &options)
{
    app.add_option("FILE", options.input, "a script, or an .aesl project (- for standard input)")
      ->required()
      ->type_name("");
    app
      .add_option("--target",
                  options.target,
                  "the node to compile for: epuck (default), dummy (the reference's\n"
                  "asebadummynode), or a target description file\n"
                  "(docs/target-description.md)")
      ->type_name("NAME|FILE");
    app
      .add_option("--node",
                  options.node,
                  "in an .aesl project, the node whose program to take (default: the\n"
                  "first one)")
      ->type_name("NAME");
    app
      .add_option("--event",
                  options.event_options,
                  "NAME[:SIZE]: declare a global event of SIZE words (default 0), for\n"
                  "scripts; with run: NAME[:a,b,...], see above")
      ->allow_extra_args(false)
      ->type_name("NAME[:SIZE]");
}

Options parse_options(int argc, char **argv)
{
    Options options;
    CLI::App app(DESCRIPTION, "asebac");
    auto formatter = command_line::use_common_style(app);
    formatter->set_usage(&app, USAGE);
    app.footer(command_line::EXIT_STATUS_TEXT);
    app.fallthrough();
    add_common_options(app, options);
    app
      .add_option("--constant",
                  options.constant_options,
                  "NAME=VALUE: declare a global constant (scripts only)")
      ->allow_extra_args(false)
      ->type_name("NAME=VALUE");
    app.add_option("-o", options.output, "write the bytecode to FILE (- for standard output)")
      ->type_name("FILE");
    app
      .add_option("--format",
                  options.format,
                  "bytecode format: binary (16-bit little-endian words), hex (one\n"
                  "0xXXXX word per line, the default) or c (a C array)")
      ->check(CLI::IsMember({ "binary", "hex", "c" }))
      ->type_name("FORMAT");
    app.add_flag("--listing", options.listing, "print the disassembly with source lines");
    app.add_flag(
      "--variables",
      options.variables,
      "print the variable map: name, address, size (locals too, with their handler or subroutine)");

    CLI::App *run = app.add_subcommand("run", "compile FILE and run it on the host VM");
    formatter->set_usage(run, "usage: asebac run [options] FILE", RUN_DESCRIPTION);
    add_common_options(*run, options);
    run
      ->add_option("--steps",
                   options.steps,
                   "instruction budget of init and of each event (default 10000); an\n"
                   "event still running after it is reported as unfinished")
      ->check(CLI::Range(1ul, 1000000000ul))
      ->type_name("N");
    // `asebac run` takes the file as its own argument.
    app.get_option("FILE")->required(false);

    command_line::parse_or_exit(app, argc, argv);
    options.run = run->parsed();
    if (options.input.empty())
        usage_error("no input file");
    return options;
}

std::string read_input(const std::string &path)
{
    if (path == "-")
        return std::string(std::istreambuf_iterator<char>(std::cin), {});
    std::ifstream file(path, std::ios::binary);
    if (!file)
        usage_error("cannot read " + path);
    return std::string(std::istreambuf_iterator<char>(file), {});
}

TargetDescription load_target(const std::string &name)
{
    if (std::optional<TargetDescription> preset = target_preset(name))
        return *preset;
    TargetReadResult read = read_target_json(read_input(name));
    if (!read.ok)
        usage_error(name + ": " + read.error);
    return read.target;
}

// An --event value split into name and what follows the colon.
std::pair<std::string, std::string> split_event(const std::string &option)
{
    size_t colon = option.find(':');
    if (colon == std::string::npos)
        return { option, "" };
    return { option.substr(0, colon), option.substr(colon + 1) };
}

std::vector<int16_t> event_arguments(const std::string &text)
{
    std::vector<int16_t> arguments;
    std::stringstream list(text);
    std::string item;
    while (std::getline(list, item, ',')) {
        std::optional<long> number = parse_integer(item);
        if (!number || *number < -32768 || *number > 65535)
            usage_error("bad event argument " + item);
        arguments.push_back(static_cast<int16_t>(*number));
    }
    return arguments;
}

bool is_declared(const CommonDefinitions &definitions, const std::string &name)
{
    for (const auto &event : definitions.events)
        if (event.name == name)
            return true;
    return false;
}

bool is_local_event(const TargetDescription &target, const std::string &name)
{
    for (const auto &event : target.local_events)
        if (event.name == name)
            return true;
    return false;
}

void write_bytecode(const Options &options, const std::vector<uint16_t> &bytecode)
{
    std::string data;
    if (options.format == "binary") {
        for (uint16_t word : bytecode) {
            data += static_cast<char>(word & 0xFF);
            data += static_cast<char>(word >> 8);
        }
    } else if (options.format == "hex") {
        char text[16];
        for (uint16_t word : bytecode) {
            std::snprintf(text, sizeof text, "0x%04x\n", word);
            data += text;
        }
    } else {
        char text[16];
        data = "// Aseba bytecode, " + std::to_string(bytecode.size()) + " words\n";
        data += "const unsigned short aseba_bytecode[" + std::to_string(bytecode.size()) + "] = {";
        for (size_t i = 0; i < bytecode.size(); ++i) {
            std::snprintf(text, sizeof text, "0x%04x,", bytecode[i]);
            data += (i % 8 == 0 ? "\n    " : " ") + std::string(text);
        }
        data += "\n};\n";
    }
    if (options.output == "-") {
        std::cout << data; // checked as the program ends
        return;
    }
    if (std::string error = command_line::write_whole_file(options.output, data); !error.empty()) {
        std::cerr << "asebac: " << error << "\n";
        std::exit(command_line::EXIT_FAILED);
    }
}

// The program; its output is checked by main.
int compile_or_run(int argc, char **argv)
{
    Options options = parse_options(argc, argv);
    TargetDescription target = load_target(options.target);
    ProgramFile program;
    try {
        program = read_program_file(options.input, options.node);
    } catch (const std::runtime_error &error) {
        std::cerr << error.what() << "\n";
        return EXIT_USAGE;
    }
    CommonDefinitions &definitions = program.definitions;

    std::vector<EventToSend> to_send;
    for (const auto &option : options.event_options) {
        auto [name, rest] = split_event(option);
        if (options.run) {
            std::vector<int16_t> arguments = event_arguments(rest);
            if (!is_declared(definitions, name) && !is_local_event(target, name))
                definitions.events.push_back({ name, static_cast<uint16_t>(arguments.size()) });
            to_send.push_back({ name, arguments });
            continue;
        }
        try {
            definitions.events.push_back(parse_event_declaration(option));
        } catch (const std::invalid_argument &error) {
            usage_error(error.what());
        }
    }
    for (const auto &option : options.constant_options) {
        size_t equal = option.find('=');
        std::optional<long> value =
          equal == std::string::npos ? std::nullopt : parse_integer(option.substr(equal + 1));
        if (!value || *value < -32768 || *value > 32767)
            usage_error("--constant needs NAME=VALUE with a 16-bit value");
        definitions.constants.push_back({ option.substr(0, equal), static_cast<int16_t>(*value) });
    }

    std::string error_text;
    CompileResult result = compile_program_file(program, target, error_text);
    if (!result.ok) {
        std::cerr << error_text;
        return 1;
    }

    if (options.run) {
        std::string report, error;
        if (!run_program(result, target, definitions, to_send, options.steps, report, error))
            usage_error(error);
        std::cout << report;
        return 0;
    }
    if (!options.output.empty())
        write_bytecode(options, result.bytecode);
    if (options.listing)
        std::cout << listing(result.bytecode, result.line_of_word, program.source);
    if (options.variables) {
        std::printf("%-24s %7s %5s\n", "variable", "address", "size");
        for (const auto &variable : result.variables)
            std::printf("%-24s %7u %5u\n", variable.name.c_str(), variable.address, variable.size);
        for (const auto &local : result.locals) // docs/language.md: where locals live
            std::printf("%-24s %7u %5u  local of %s\n",
                        local.name.c_str(),
                        local.address,
                        local.size,
                        local.owner.c_str());
        std::printf("%u of %u words used by variables (%u by the locals, shared)\n",
                    result.allocated_variables,
                    target.variables_size,
                    result.locals_words);
    }
    if (options.output.empty() && !options.listing && !options.variables)
        std::cout << program.file_name << ": " << result.bytecode.size() << " of "
                  << target.bytecode_size << " words of bytecode, " << result.allocated_variables
                  << " of " << target.variables_size << " words of variables\n";
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    return aseba::command_line::finish_standard_output("asebac", compile_or_run(argc, argv));
}
