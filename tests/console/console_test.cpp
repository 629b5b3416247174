// `aseba` end to end: the program is run as users run it, against epuck-emu
// started on a free port, and its output is checked against what the
// programs and the e-puck's description imply.

#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "console_support.hpp"
#include "tools/client/messages.hpp"

using namespace console_test;

namespace
{

bool contains(const std::string &text, const std::string &part)
{
    return text.find(part) != std::string::npos;
}

// A program whose effects the tests can predict: a counter of ir_sensors
// events, a handler computing from its arguments, and an answer event.
const char *const COUNTER_PROGRAM = R"(var counter = 0
var sum = 0

onevent ir_sensors
  counter = counter + 1

onevent ping
  sum = args[0] + args[1]
  emit pong [sum, id]
)";
const int COUNTER_LINE = 5; // counter = counter + 1

class Console : public testing::Test
{
  protected:
    explicit Console(unsigned robots = 1)
      : emulator_(robots)
    {
    }

    CommandResult aseba(std::vector<std::string> arguments)
    {
        arguments.insert(arguments.begin(), { "-t", emulator_.target() });
        return run_console(arguments, scratch_.path());
    }

    // Loads the counter program (with its two global events).
    std::string load_counter(const std::vector<std::string> &extra = {})
    {
        std::string file = scratch_.write("counter.aseba", COUNTER_PROGRAM);
        std::vector<std::string> arguments{
            "load", file, "--event", "ping:2", "--event", "pong:2"
        };
        arguments.insert(arguments.end(), extra.begin(), extra.end());
        CommandResult load = aseba(arguments);
        EXPECT_EQ(load.exit_code, 0) << load.err;
        return file;
    }

    // The integer after "NAME = " in `vars` output.
    static long value_of(const CommandResult &result, const std::string &name)
    {
        size_t at = result.out.find(name + " = ");
        EXPECT_NE(at, std::string::npos) << result.out << result.err;
        if (at == std::string::npos)
            return -99999;
        return std::stol(result.out.substr(at + name.size() + 3));
    }

    ScratchFolder scratch_;
    Emulator emulator_;
};

class ConsoleGroup : public Console
{
  protected:
    ConsoleGroup()
      : Console(3)
    {
    }
};

} // namespace

TEST(ConsoleHelp, TellsEveryCommand)
{
    ScratchFolder scratch;
    CommandResult help = run_console({ "--help" }, scratch.path());
    EXPECT_EQ(help.exit_code, 0);
    for (const char *command : { "nodes",
                                 "compile",
                                 "load",
                                 "run",
                                 "pause",
                                 "step",
                                 "stop",
                                 "reset",
                                 "break",
                                 "vars",
                                 "watch",
                                 "emit",
                                 "monitor",
                                 "save",
                                 "reboot" }) {
        EXPECT_TRUE(contains(help.out, command)) << command;
        if (std::string(command) == "pause" || std::string(command) == "step" ||
            std::string(command) == "stop" || std::string(command) == "reset")
            continue; // shown with run
        CommandResult detail = run_console({ "help", command }, scratch.path());
        EXPECT_EQ(detail.exit_code, 0) << command;
        EXPECT_TRUE(contains(detail.out, "usage: aseba " + std::string(command))) << command;
    }
    CommandResult unknown = run_console({ "fly" }, scratch.path());
    EXPECT_EQ(unknown.exit_code, 2);
    EXPECT_TRUE(contains(unknown.err, "no command 'fly'"));
}

TEST(ConsoleErrors, NoNetworkIsAClearFailure)
{
    ScratchFolder scratch;
    // Port 1 of the loopback: nobody listens.
    CommandResult nodes = run_console({ "-t", "tcp:127.0.0.1;1", "nodes" }, scratch.path());
    EXPECT_EQ(nodes.exit_code, 1);
    EXPECT_TRUE(contains(nodes.err, "cannot connect")) << nodes.err;
}

// A network member names its node, variables, events and natives as it
// likes: a node named as below cleared the screen of whoever listed the
// nodes, and set the title of their window. What comes from the network
// reaches the terminal escaped, in listings as in error messages.
TEST(ConsoleErrors, TextsFromTheNetworkReachTheTerminalEscaped)
{
    using namespace aseba::client;
    const std::string attack = "\x1b[2J\x1b[31mPWNED\x07\x1b]0;title\x07";
    const std::string shown = "\\x1b[2J\\x1b[31mPWNED\\x07\\x1b]0;title\\x07";
    const std::string csi = "\xc2\x9b"; // the C1 control CSI, in UTF-8
    // A node (id 5) that describes itself with these names and never
    // answers execution commands, so that they also end in an error.
    auto answer = [&](const Frame &frame) {
        std::vector<Frame> replies;
        Message message = decode(frame);
        if (std::holds_alternative<ListNodes>(message)) {
            replies.push_back(encode(NodePresent{ 5 }, 5));
        } else if (std::holds_alternative<GetNodeDescription>(message)) {
            replies.push_back(encode(Description{ attack, 5, 100, 16, 40, 1, 1, 1 }, 5));
            replies.push_back(encode(NamedVariableDescription{ { attack + "var", 1 } }, 5));
            replies.push_back(encode(LocalEventDescription{ { attack, csi + "[2J" } }, 5));
            replies.push_back(
              encode(NativeFunctionDescription{ { "f" + attack, attack, { { attack, 1 } } } }, 5));
        }
        return replies;
    };
    ScratchFolder scratch;
    for (const std::vector<std::string> &command :
         { std::vector<std::string>{ "nodes", "--describe" }, { "run" } }) {
        SCOPED_TRACE(command.front());
        ScriptedPeer peer(answer);
        std::vector<std::string> arguments{ "-t", peer.target(), "--timeout", "300" };
        arguments.insert(arguments.end(), command.begin(), command.end());
        CommandResult result = run_console(arguments, scratch.path());
        std::string printed = result.out + result.err;
        EXPECT_EQ(printed.find_first_of("\x1b\x07"), std::string::npos) << printed;
        EXPECT_EQ(printed.find(csi), std::string::npos) << printed;
        EXPECT_TRUE(contains(printed, shown)) << printed;
    }
}

TEST_F(Console, NodesListsAndDescribesTheRobot)
{
    CommandResult nodes = aseba({ "nodes" });
    ASSERT_EQ(nodes.exit_code, 0) << nodes.err;
    ASSERT_EQ(lines_of(nodes.out).size(), 1u) << nodes.out;
    EXPECT_TRUE(contains(nodes.out, "node 1 \"e-puck\"")) << nodes.out;
    EXPECT_TRUE(contains(nodes.out, "protocol 5"));
    EXPECT_TRUE(contains(nodes.out, "bytecode 1024 words")); // FIRMWARE_BYTECODE_WORDS

    CommandResult described = aseba({ "nodes", "--describe" });
    ASSERT_EQ(described.exit_code, 0) << described.err;
    // The e-puck's variables of hardware/epuck1.md §6.1, in memory order.
    EXPECT_TRUE(contains(described.out,
                         "variables: id source args[32] leftSpeed rightSpeed "
                         "leds[8] prox[8] ambiant[8] acc[3] camLine camR[60] "
                         "camG[60] camB[60] steps.left steps.right mic[3] sel rc5 "
                         "timer.period battery mic.samples0[32] mic.samples1[32] "
                         "mic.samples2[32]"))
      << described.out;
    EXPECT_TRUE(contains(described.out, "local events: ir_sensors camera timer microphones"));
    EXPECT_TRUE(contains(described.out, "math.fill(dest[<1>], value)")) << described.out;

    CommandResult unknown = aseba({ "nodes", "--node", "9" });
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_TRUE(contains(unknown.err, "no node '9'")) << unknown.err;
}

TEST_F(Console, LoadRunsTheProgramAndVarsReadsIt)
{
    load_counter();
    // ir_sensors fires by itself: the counter grows while the program runs.
    CommandResult first = aseba({ "vars", "counter" });
    ASSERT_EQ(first.exit_code, 0) << first.err;
    std::this_thread::sleep_for(Milliseconds(200));
    CommandResult second = aseba({ "vars", "counter" });
    EXPECT_GT(value_of(second, "counter"), value_of(first, "counter"));
}

TEST_F(Console, VarsWritesAndReadsSlices)
{
    CommandResult write = aseba({ "vars", "leds[2:4]=5,-6,7" });
    ASSERT_EQ(write.exit_code, 0) << write.err;
    CommandResult read = aseba({ "vars", "leds" });
    EXPECT_EQ(read.out, "leds = 0 0 5 -6 7 0 0 0\n") << read.err;
    CommandResult spaced = aseba({ "vars", "leftSpeed", "=", "-300" });
    ASSERT_EQ(spaced.exit_code, 0) << spaced.err;
    EXPECT_EQ(aseba({ "vars", "leftSpeed", "leds[3]" }).out, "leftSpeed = -300\nleds[3] = -6\n");
    CommandResult too_far = aseba({ "vars", "leds[8]" });
    EXPECT_EQ(too_far.exit_code, 1);
    EXPECT_TRUE(contains(too_far.err, "index 8 is out of range")) << too_far.err;
    CommandResult unknown = aseba({ "vars", "speed" });
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_TRUE(contains(unknown.err, "no variable 'speed'")) << unknown.err;
}

TEST_F(Console, EmitReachesTheHandlerAndMonitorSeesTheAnswer)
{
    load_counter();
    BackgroundConsole monitor(
      { "-t", emulator_.target(), "monitor", "--event", "pong", "--duration", "3", "--count", "1" },
      scratch_.path());
    std::this_thread::sleep_for(Milliseconds(500)); // the monitor connects
    CommandResult emit = aseba({ "emit", "ping", "30", "12" });
    ASSERT_EQ(emit.exit_code, 0) << emit.err;
    EXPECT_EQ(emit.out, "sent event ping(30, 12)\n");
    CommandResult monitored = monitor.finish(Milliseconds(5000));
    EXPECT_EQ(monitored.exit_code, 0) << monitored.err;
    // The handler computed 30 + 12 and answered with its id, 1.
    EXPECT_TRUE(contains(monitored.out, "e-puck 1  event pong(42, 1)")) << monitored.out;
    EXPECT_EQ(value_of(aseba({ "vars", "sum" }), "sum"), 42);

    CommandResult wrong = aseba({ "emit", "ping", "1" });
    EXPECT_EQ(wrong.exit_code, 2);
    EXPECT_TRUE(contains(wrong.err, "event ping has 2 arguments, 1 given")) << wrong.err;
}

TEST_F(Console, ExecutionStates)
{
    load_counter({ "--paused" });
    // After an upload the node is reset, in step-by-step mode.
    CommandResult step = aseba({ "step" });
    ASSERT_EQ(step.exit_code, 0) << step.err;
    EXPECT_TRUE(contains(step.out, "e-puck 1: stepping at pc")) << step.out;
    CommandResult run = aseba({ "run" });
    EXPECT_TRUE(contains(run.out, "e-puck 1: running")) << run.out;
    CommandResult stop = aseba({ "stop" });
    EXPECT_EQ(stop.out, "e-puck 1: stopped\n") << stop.err;
    // Stopped: ir_sensors still starts its handler, which then waits for steps.
    CommandResult paused = aseba({ "pause" });
    EXPECT_TRUE(contains(paused.out, "e-puck 1: st")) << paused.out;
    long before = value_of(aseba({ "vars", "counter" }), "counter");
    std::this_thread::sleep_for(Milliseconds(150));
    EXPECT_EQ(value_of(aseba({ "vars", "counter" }), "counter"), before);
    EXPECT_TRUE(contains(aseba({ "run" }).out, "running"));
    std::this_thread::sleep_for(Milliseconds(150));
    EXPECT_GT(value_of(aseba({ "vars", "counter" }), "counter"), before);
}

TEST_F(Console, BreakpointHitIsReportedWithItsLine)
{
    load_counter();
    CommandResult set = aseba({ "break", "set", std::to_string(COUNTER_LINE), "--wait" });
    ASSERT_EQ(set.exit_code, 0) << set.out << set.err;
    EXPECT_TRUE(contains(set.out, "breakpoint set at line 5")) << set.out;
    EXPECT_TRUE(contains(set.out, "breakpoint hit at pc")) << set.out;
    EXPECT_TRUE(contains(set.out, "line 5:   counter = counter + 1")) << set.out;
    // Held on the breakpoint, the counter does not move.
    long held = value_of(aseba({ "vars", "counter" }), "counter");
    std::this_thread::sleep_for(Milliseconds(150));
    EXPECT_EQ(value_of(aseba({ "vars", "counter" }), "counter"), held);
    CommandResult clear = aseba({ "break", "clear", "all" });
    EXPECT_EQ(clear.exit_code, 0);
    EXPECT_TRUE(contains(aseba({ "run" }).out, "running"));
    std::this_thread::sleep_for(Milliseconds(150));
    EXPECT_GT(value_of(aseba({ "vars", "counter" }), "counter"), held);
    CommandResult nowhere = aseba({ "break", "set", "3" }); // an empty line
    EXPECT_EQ(nowhere.exit_code, 1);
    EXPECT_TRUE(contains(nowhere.err, "no code on line 3")) << nowhere.err;
}

TEST_F(Console, CompileErrorsShowFileLineColumnAndCaret)
{
    std::string file = scratch_.write("broken.aseba", "var x = 0\nx = y + 1\n");
    CommandResult compile = aseba({ "compile", file });
    EXPECT_EQ(compile.exit_code, 1);
    EXPECT_TRUE(contains(compile.err, file + ":2:5: error:")) << compile.err;
    EXPECT_TRUE(contains(compile.err, "^")) << compile.err;
    CommandResult load = aseba({ "load", file });
    EXPECT_EQ(load.exit_code, 1);
    std::string good = scratch_.write("good.aseba", "var x = 3\n");
    CommandResult ok = aseba({ "compile", good });
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
    EXPECT_TRUE(contains(ok.out, "for e-puck 1:")) << ok.out;
}

TEST_F(ConsoleGroup, AllRobotsAtOnce)
{
    CommandResult ids = aseba({ "vars", "id", "--node", "all" });
    ASSERT_EQ(ids.exit_code, 0) << ids.err;
    EXPECT_EQ(ids.out, "e-puck 1: id = 1\ne-puck 2: id = 2\ne-puck 3: id = 3\n");
    load_counter({ "--node", "all" });
    CommandResult watch = aseba({ "watch", "id", "counter", "--count", "2", "--interval", "50" });
    ASSERT_EQ(watch.exit_code, 0) << watch.err;
    std::vector<std::string> lines = lines_of(watch.out);
    // Two tables: a header and three rows each, a blank line between.
    ASSERT_EQ(lines.size(), 9u) << watch.out;
    EXPECT_TRUE(contains(lines[0], "node")) << watch.out;
    EXPECT_TRUE(contains(lines[0], "counter"));
    for (int row = 1; row <= 3; row++)
        EXPECT_EQ(lines[size_t(row)].rfind("e-puck " + std::to_string(row), 0), 0u) << watch.out;
    CommandResult emit = aseba({ "emit", "ping", "2", "3" });
    ASSERT_EQ(emit.exit_code, 0) << emit.err;
    CommandResult sums = aseba({ "vars", "sum" });
    EXPECT_EQ(sums.out, "e-puck 1: sum = 5\ne-puck 2: sum = 5\ne-puck 3: sum = 5\n");
    CommandResult second = aseba({ "stop", "--node", "2" });
    EXPECT_EQ(second.out, "e-puck 2: stopped\n") << second.err;
}

// The paper's project file: its init sets camLine to 32 on every robot, and
// its global event `bad` is known by name afterwards.
TEST_F(ConsoleGroup, LoadsAnAeslProjectOnEveryRobot)
{
    CommandResult load = aseba({ "load", "examples/paper-annex.aesl" });
    ASSERT_EQ(load.exit_code, 0) << load.err;
    EXPECT_EQ(lines_of(load.out).size(), 3u) << load.out;
    CommandResult lines = aseba({ "vars", "camLine" });
    EXPECT_EQ(lines.out, "e-puck 1: camLine = 32\ne-puck 2: camLine = 32\ne-puck 3: camLine = 32\n")
      << lines.err;
    CommandResult emit = aseba({ "emit", "bad", "2" });
    EXPECT_EQ(emit.exit_code, 0) << emit.err;
    EXPECT_EQ(emit.out, "sent event bad(2)\n");
    CommandResult help = aseba({ "vars", "--help" });
    EXPECT_TRUE(contains(help.out, "usage: aseba vars")) << help.out;
}

// Studio's "Next": one source line per `step --line`, through a handler
// started while the node is stopped; the arithmetic of the three lines gives
// a = 1, b = 1 * 2 + 3 = 5, then a = 5 - 1 = 4.
TEST_F(Console, StepByLineWalksTheSource)
{
    std::string file = scratch_.write("lines.aseba",
                                      "var a = 0\nvar b = 0\n\nonevent ping\n"
                                      "  a = a + 1\n  b = a * 2 + 3\n  a = b - 1\n");
    ASSERT_EQ(aseba({ "load", file, "--event", "ping:0", "--paused" }).exit_code, 0);
    EXPECT_EQ(aseba({ "stop" }).out, "e-puck 1: stopped\n");
    ASSERT_EQ(aseba({ "emit", "ping" }).exit_code, 0);
    // Stopped, the event's handler starts and waits at its first line.
    CommandResult first = aseba({ "step", "--line" });
    EXPECT_TRUE(contains(first.out, "line 6:   b = a * 2 + 3")) << first.out << first.err;
    CommandResult second = aseba({ "step", "--line" });
    EXPECT_TRUE(contains(second.out, "line 7:   a = b - 1")) << second.out;
    CommandResult last = aseba({ "step", "--line" });
    EXPECT_EQ(last.out, "e-puck 1: stopped\n");
    EXPECT_EQ(aseba({ "vars", "a", "b" }).out, "a = 4\nb = 5\n");
}

// save and reboot expect no answer (protocol.md §6.8); another client on the
// network sees the commands go out, addressed to the robot.
TEST_F(Console, SaveAndRebootReachTheNetwork)
{
    BackgroundConsole monitor({ "-t", emulator_.target(), "monitor", "--all", "--duration", "2" },
                              scratch_.path());
    std::this_thread::sleep_for(Milliseconds(500)); // the monitor connects
    CommandResult save = aseba({ "save" });
    EXPECT_EQ(save.exit_code, 0) << save.err;
    CommandResult reboot = aseba({ "reboot", "--node", "1" });
    EXPECT_EQ(reboot.exit_code, 0) << reboot.err;
    CommandResult monitored = monitor.finish(Milliseconds(5000));
    EXPECT_TRUE(contains(monitored.out, "host  WRITE_BYTECODE to 1")) << monitored.out;
    EXPECT_TRUE(contains(monitored.out, "host  REBOOT to 1")) << monitored.out;
    EXPECT_EQ(aseba({ "nodes" }).exit_code, 0); // still answering
}
