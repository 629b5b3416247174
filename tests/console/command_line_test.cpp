// The command lines of every program (asebac, aseba, epuck-emu,
// epuck-image, aseba-ide, aseba-mqtt), run as a user runs them: one style of
// help and errors, and one set of exit statuses (0 success, 1 the work
// failed, 2 bad usage or an input file that cannot be read or used), output
// that could not be written included. Inputs that once crashed the programs
// (a deeply nested project), were blamed on the wrong file (a target
// description) or took minutes to read are among them.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "console_support.hpp"
#include "tests/bootloader/test_images.hpp"

using namespace console_test;

namespace
{

const char *const PROGRAMS[] = { "asebac", "aseba", "epuck-emu", "epuck-image" };

bool contains(const std::string &text, const std::string &part)
{
    return text.find(part) != std::string::npos;
}

// An .aesl project whose node holds `depth` nested elements.
std::string deep_project(int depth)
{
    std::string open, close;
    for (int i = 0; i < depth; i++) {
        open += "<a>";
        close += "</a>";
    }
    return "<!DOCTYPE aesl-source>\n<network>\n<node name=\"e-puck\" nodeId=\"1\">" + open + close +
           "</node>\n</network>\n";
}

} // namespace

TEST(CommandLines, HelpStartsWithUsageAndExitsZero)
{
    ScratchFolder scratch;
    for (const char *program : PROGRAMS) {
        CommandResult help = run_program(program, { "--help" }, scratch.path());
        EXPECT_EQ(help.exit_code, 0) << program << help.err;
        EXPECT_EQ(help.out.rfind(std::string("usage: ") + program, 0), 0u) << help.out;
        EXPECT_TRUE(contains(help.out, "Exit status: 0")) << program << "\n" << help.out;
    }
    CommandResult install = run_program("epuck-image", { "install", "--help" }, scratch.path());
    EXPECT_EQ(install.exit_code, 0);
    EXPECT_EQ(install.out.rfind("usage: epuck-image install --port DEVICE", 0), 0u) << install.out;
}

TEST(CommandLines, AnUnknownOptionIsAUsageErrorNamedAsSuch)
{
    ScratchFolder scratch;
    for (const char *program : PROGRAMS) {
        // epuck-image's four files are given, so only the option is wrong.
        CommandResult bogus =
          run_program(program, { "--bogus", "a.hex", "b.hex", "c.hex", "d.hex" }, scratch.path());
        EXPECT_EQ(bogus.exit_code, 2) << program;
        EXPECT_TRUE(contains(bogus.err, std::string(program) + ": ")) << bogus.err;
        EXPECT_TRUE(contains(bogus.err, "--bogus")) << program << ": " << bogus.err;
        EXPECT_TRUE(contains(bogus.err, "--help for usage")) << program << ": " << bogus.err;
        EXPECT_FALSE(contains(bogus.err, "cannot be read")) << program << ": " << bogus.err;
    }
    CommandResult range = run_program("epuck-emu", { "--robots", "0" }, scratch.path());
    EXPECT_EQ(range.exit_code, 2);
    EXPECT_TRUE(contains(range.err, "--robots")) << range.err;
}

// An input file that cannot be read is status 2 from every program (it was
// 2 from asebac and 1 from aseba), before any network is touched.
TEST(CommandLines, AnUnreadableInputFileIsStatusTwoEverywhere)
{
    ScratchFolder scratch;
    const std::string missing = scratch.path() + "/missing.aesl";
    struct Run {
        const char *program;
        std::vector<std::string> arguments;
    };
    // Port 1: nobody listens there, so a network failure would be status 1.
    const Run runs[] = {
        { "asebac", { missing } },
        { "aseba", { "-t", "tcp:127.0.0.1;1", "load", missing } },
        { "aseba", { "-t", "tcp:127.0.0.1;1", "compile", missing } },
        { "aseba", { "-t", "tcp:127.0.0.1;1", "vars", "-p", missing } },
        { "aseba", { "-t", "tcp:127.0.0.1;1", "flash", scratch.path() + "/missing.hex" } },
        { "epuck-emu", { "--load", missing, "--port", "1" } },
        { "epuck-image", { missing, missing, missing, missing } },
    };
    for (const Run &run : runs) {
        CommandResult result = run_program(run.program, run.arguments, scratch.path());
        EXPECT_EQ(result.exit_code, 2) << run.program << " " << run.arguments.back() << "\n"
                                       << result.err;
        EXPECT_TRUE(contains(result.err, "missing.")) << run.program << ": " << result.err;
    }
}

// 50,000 nested elements crashed asebac and epuck-emu --load (the
// hand-written XML reader recursed per element).
TEST(CommandLines, ADeeplyNestedProjectIsNoCrash)
{
    ScratchFolder scratch;
    std::string deep = scratch.write("deep.aesl", deep_project(50000));
    CommandResult compiled = run_program("asebac", { deep }, scratch.path());
    EXPECT_GE(compiled.exit_code, 0) << compiled.err; // not killed by a signal
    EXPECT_LE(compiled.exit_code, 2) << compiled.err;
    CommandResult emulated = run_program(
      "epuck-emu",
      { "--load", deep, "--duration", "0.1", "--port", std::to_string(find_free_port()) },
      scratch.path());
    EXPECT_GE(emulated.exit_code, 0) << emulated.err;
    EXPECT_LE(emulated.exit_code, 2) << emulated.err;

    std::string unclosed =
      scratch.write("unclosed.aesl", "<network>\n<node name=\"e-puck\"><a><a>");
    CommandResult refused = run_program("asebac", { unclosed }, scratch.path());
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_TRUE(contains(refused.err, "unclosed.aesl:2:")) << refused.err;
}

// A target description that cannot be right is the target file's fault:
// named, status 2 (it was blamed on the script, status 1).
TEST(CommandLines, AWrongTargetDescriptionNamesItsFile)
{
    ScratchFolder scratch;
    std::string target = scratch.write("tiny.json", R"({
        "name": "tiny", "bytecode_size": 100, "variables_size": 4, "stack_size": 16,
        "variables": [{"name": "id"}, {"name": "source"}, {"name": "args", "size": 32}]
    })");
    std::string script = scratch.write("script.aseba", "var x = 1\n");
    CommandResult result = run_program("asebac", { "--target", target, script }, scratch.path());
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_TRUE(contains(result.err,
                         "tiny.json: variables: the named variables take 34 words, "
                         "more than variables_size (4)"))
      << result.err;
    EXPECT_FALSE(contains(result.err, "script.aseba")) << result.err;

    std::string twice = scratch.write("twice.json", R"({
        "name": "twice", "bytecode_size": 100, "variables_size": 40, "stack_size": 16,
        "local_events": [{"name": "tick"}, {"name": "tick"}]
    })");
    result = run_program("asebac", { "--target", twice, script }, scratch.path());
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_TRUE(contains(result.err, "twice.json: local_events[1]: the name tick is used twice"))
      << result.err;
}

// A compile error is the work failing: status 1.
TEST(CommandLines, ACompileErrorIsStatusOne)
{
    ScratchFolder scratch;
    std::string script = scratch.write("wrong.aseba", "x = 1\n");
    CommandResult result = run_program("asebac", { script }, scratch.path());
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_TRUE(contains(result.err, "wrong.aseba:1:")) << result.err;
}

// A global event declared on a command line holds at most the protocol's 258
// words of arguments (protocol.md §2); the console once wrapped a larger size
// into 16 bits.
TEST(CommandLines, AnEventLargerThanTheProtocolIsAUsageError)
{
    ScratchFolder scratch;
    std::string script = scratch.write("script.aseba", "var x = 1\n");
    CommandResult largest = run_program("asebac", { "--event", "big:258", script }, scratch.path());
    EXPECT_EQ(largest.exit_code, 0) << largest.err;
    // Port 1: nobody listens there; the command line is refused first.
    const std::vector<std::vector<std::string>> runs = {
        { "asebac", "--event", "big:259", script },
        { "aseba", "-t", "tcp:127.0.0.1;1", "load", script, "--event", "big:65794" },
        { "aseba-mqtt", "-t", "tcp:127.0.0.1;1", "--event", "big:259" },
        { "aseba", "-t", "tcp:127.0.0.1;1", "load", script, "--event", ":2" },
    };
    for (const auto &run : runs) {
        std::vector<std::string> arguments(run.begin() + 1, run.end());
        CommandResult result = run_program(run.front(), arguments, scratch.path());
        EXPECT_EQ(result.exit_code, 2) << run.front() << " " << arguments.back() << result.err;
        EXPECT_TRUE(contains(result.err, "--event")) << run.front() << ": " << result.err;
    }
}

// A target that is no target at all is bad usage (2); a target that cannot
// be reached, and a port already taken, are the work failing (1).
TEST(CommandLines, ATargetThatIsNoneIsUsageAndAPortInUseIsAFailure)
{
    ScratchFolder scratch;
    CommandResult malformed = run_console({ "-t", "foo", "nodes" }, scratch.path());
    EXPECT_EQ(malformed.exit_code, 2) << malformed.err;
    EXPECT_TRUE(contains(malformed.err, "'foo' is none of")) << malformed.err;

    Emulator first(1);
    for (const std::vector<std::string> &arguments :
         { std::vector<std::string>{
             "--robots", "1", "--duration", "5", "--port", std::to_string(first.port()) },
           std::vector<std::string>{ "--arena",
                                     "default",
                                     "--robots",
                                     "1",
                                     "--duration",
                                     "5",
                                     "--port",
                                     std::to_string(first.port()) } }) {
        CommandResult second = run_program("epuck-emu", arguments, scratch.path());
        EXPECT_EQ(second.exit_code, 1) << second.err;
        EXPECT_TRUE(contains(second.err, "Address already in use")) << second.err;
    }
}

// Reading was quadratic in the size of the input: an .aesl project of
// 40,000 nodes took asebac 73 s (each node's line was found by scanning the
// text before it), a description of 32,767 local events (the most the
// bytecode allows) half a minute (the JSON parser's callback). Both are read
// within the usual wait now, and a node deep in the file still has its line.
TEST(CommandLines, LargeProjectsAndDescriptionsAreReadWithinTheWait)
{
    ScratchFolder scratch;
    constexpr int nodes = 40000;
    std::string project = "<!DOCTYPE aesl-source>\n<network>\n";
    for (int i = 1; i < nodes; i++)
        project += "<node nodeId=\"" + std::to_string(i) + "\" name=\"n\">var x</node>\n";
    project += "<node nodeId=\"1\" name=\"last\">var x\nx = y\n</node>\n</network>\n";
    std::string path = scratch.write("large.aesl", project);
    CommandResult compiled = run_program("asebac", { path, "--node", "last" }, scratch.path());
    EXPECT_EQ(compiled.exit_code, 1) << compiled.err;
    // Lines 1 and 2, then the 39,999 others: the last node's second line.
    EXPECT_TRUE(contains(compiled.err, "large.aesl:" + std::to_string(2 + nodes + 1) + ":"))
      << compiled.err.substr(0, 300);

    std::string events;
    for (int i = 0; i < 32767; i++)
        events += std::string(i == 0 ? "" : ",") + "{\"name\": \"e" + std::to_string(i) + "\"}";
    std::string target = scratch.write(
      "large.json",
      R"({"name": "large", "bytecode_size": 100, "variables_size": 40, "stack_size": 16,
          "local_events": [)" +
        events + "]}");
    std::string script = scratch.write("handler.aseba", "var x\nonevent e32766\nx = 1\n");
    CommandResult described = run_program("asebac", { "--target", target, script }, scratch.path());
    EXPECT_EQ(described.exit_code, 0) << described.err;
}

// A program's output that cannot be written (a full disk, a closed pipe) is
// the work failing, said on standard error: asebac once exited 0 after
// writing its bytecode to /dev/full. Each program, for what it writes: its
// help, and its own output.
struct FullOutput {
    const char *program;
    // "PORT": a free port, "NETWORK": epuck-emu's target, "BOOTLOADER": a
    // bootloader image, "SCRATCH/NAME": a file of the test's folder.
    std::vector<std::string> arguments;
    bool to_standard_output; // else an argument names /dev/full
};

void PrintTo(const FullOutput &run, std::ostream *out)
{
    *out << run.program;
    for (const std::string &argument : run.arguments)
        *out << " " << argument;
    *out << (run.to_standard_output ? " > /dev/full" : "");
}

class OutputErrors : public testing::TestWithParam<FullOutput>
{
};

TEST_P(OutputErrors, AreStatusOneWithAMessage)
{
    const FullOutput &run = GetParam();
    ScratchFolder scratch;
    std::unique_ptr<Emulator> emulator;
    std::vector<std::string> arguments;
    for (const std::string &argument : run.arguments) {
        if (argument == "NETWORK") {
            emulator = std::make_unique<Emulator>();
            arguments.push_back(emulator->target());
        } else if (argument == "PORT") {
            arguments.push_back(std::to_string(find_free_port()));
        } else if (argument.rfind("SCRATCH/", 0) == 0) {
            arguments.push_back(scratch.path() + argument.substr(7));
        } else if (argument == "BOOTLOADER") {
            arguments.push_back(scratch.write(
              "bootloader.hex",
              aseba::flash::write_microchip_hex(bootloader_test::bootloader_image())));
        } else {
            arguments.push_back(argument);
        }
    }
    CommandResult result = run_program(run.program,
                                       arguments,
                                       scratch.path(),
                                       Milliseconds(20000),
                                       run.to_standard_output ? "/dev/full" : "");
    EXPECT_EQ(result.exit_code, 1) << result.err;
    std::string complaint =
      run.to_standard_output ? "cannot write to standard output" : "/dev/full: cannot be written";
    EXPECT_TRUE(contains(result.err, std::string(run.program) + ": ")) << result.err;
    EXPECT_TRUE(contains(result.err, complaint)) << result.err;
}

const FullOutput full_outputs[] = {
    { "asebac", { "--help" }, true },
    { "asebac", { "examples/paper-annex.aesl", "-o", "/dev/full", "--format", "binary" }, false },
    { "asebac", { "examples/paper-annex.aesl", "-o", "-" }, true },
    { "asebac", { "examples/paper-annex.aesl", "--listing" }, true },
    { "asebac", { "run", "examples/paper-annex.aesl" }, true },
    { "aseba", { "--help" }, true },
    { "aseba", { "-t", "NETWORK", "nodes" }, true },
    { "epuck-emu", { "--help" }, true },
    { "epuck-emu", { "--port", "PORT", "--duration", "0.2" }, true },
    { "epuck-image", { "--help" }, true },
    { "epuck-image",
      { "tests/bootloader/hex/application.hex", "BOOTLOADER", "/dev/full", "SCRATCH/factory.hex" },
      false },
    { "aseba-ide", { "--help" }, true },
    { "aseba-ide", { "--port", "0", "tcp:127.0.0.1;1" }, true },
    { "aseba-mqtt", { "--help" }, true },
};

INSTANTIATE_TEST_SUITE_P(EveryProgram,
                         OutputErrors,
                         testing::ValuesIn(full_outputs),
                         [](const testing::TestParamInfo<FullOutput> &parameter) {
                             std::string name = std::string(parameter.param.program) + "_" +
                                                std::to_string(parameter.index);
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });
