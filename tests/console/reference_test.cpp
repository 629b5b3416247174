// `aseba` against a reference node: an e-puck of Debian's asebaplayground
// (headless), behind Debian's asebaswitch (the playground serves one client
// at a time, and each console command is a new client). Skipped when the
// reference tools are not installed.

#include <gtest/gtest.h>

#include <thread>

#include "console_support.hpp"

using namespace console_test;

namespace
{

const Milliseconds START_LIMIT{ 10000 };
const Milliseconds POLL_INTERVAL{ 50 };
// The playground may crash when a client connects while it starts
// (reference-tools.md): wait this long once its port listens.
const Milliseconds SETTLE_AFTER_LISTEN{ 1000 };

bool wait_listening(uint16_t port, ReferenceProgram &program)
{
    auto deadline = std::chrono::steady_clock::now() + START_LIMIT;
    while (std::chrono::steady_clock::now() < deadline) {
        if (is_listening(port))
            return true;
        if (!program.running())
            return false;
        std::this_thread::sleep_for(POLL_INTERVAL);
    }
    return false;
}

bool contains(const std::string &text, const std::string &part)
{
    return text.find(part) != std::string::npos;
}

} // namespace

TEST(ReferencePlayground, ConsoleDrivesAPlaygroundEpuck)
{
    // The project's install script provides them; a missing tool is a failure.
    ASSERT_TRUE(in_path("asebaplayground") && in_path("asebaswitch"))
      << "Debian's aseba tools are not installed: run scripts/install-deps.sh";
    ScratchFolder scratch;
    uint16_t robot_port = find_free_port();
    // A small arena with one e-puck listening on robot_port, node id 1.
    std::string scene =
      scratch.write("arena.playground",
                    "<!DOCTYPE aseba-playground>\n<aseba-playground>\n"
                    "<color name=\"wall\" r=\"0.9\" g=\"0.9\" b=\"0.9\"/>\n"
                    "<world w=\"110\" h=\"110\" color=\"wall\"/>\n"
                    "<robot type=\"e-puck\" x=\"40\" y=\"40\" port=\"" +
                      std::to_string(robot_port) + "\" nodeId=\"1\"/>\n</aseba-playground>\n");
    ReferenceProgram playground(
      { "asebaplayground", scene },
      { "QT_QPA_PLATFORM=offscreen", "XDG_RUNTIME_DIR=" + scratch.path() },
      scratch.path() + "/playground.log");
    ASSERT_TRUE(wait_listening(robot_port, playground)) << "asebaplayground did not start";
    std::this_thread::sleep_for(SETTLE_AFTER_LISTEN);

    uint16_t switch_port = find_free_port();
    ReferenceProgram relay({ "asebaswitch",
                             "-p",
                             std::to_string(switch_port),
                             "tcp:localhost;" + std::to_string(robot_port) },
                           {},
                           scratch.path() + "/switch.log");
    ASSERT_TRUE(wait_listening(switch_port, relay)) << "asebaswitch did not start";
    std::string target = "tcp:localhost;" + std::to_string(switch_port);
    auto aseba = [&](std::vector<std::string> arguments) {
        arguments.insert(arguments.begin(), { "-t", target, "--timeout", "2000" });
        return run_console(arguments, scratch.path());
    };

    // The playground's e-puck describes itself with its own variables
    // (reference-tools.md): speed.left/right, prox[8], cam.red[60], energy.
    CommandResult nodes = aseba({ "nodes", "--describe" });
    ASSERT_EQ(nodes.exit_code, 0) << nodes.err;
    EXPECT_TRUE(contains(nodes.out, "node 1 \"e-puck0\"")) << nodes.out;
    EXPECT_TRUE(contains(nodes.out, "speed.left")) << nodes.out;
    EXPECT_TRUE(contains(nodes.out, "cam.red[60]")) << nodes.out;
    EXPECT_TRUE(contains(nodes.out, "energy.send(amount)")) << nodes.out;

    std::string program = scratch.write("counter.aseba", R"(var counter = 0
var sum = 0

onevent ir_sensors
  counter = counter + 1

onevent ping
  sum = args[0] + args[1]
  emit pong [sum, id]
)");
    CommandResult load = aseba({ "load", program, "--event", "ping:2", "--event", "pong:2" });
    ASSERT_EQ(load.exit_code, 0) << load.err;
    EXPECT_TRUE(contains(load.out, "running")) << load.out;
    std::this_thread::sleep_for(Milliseconds(300)); // ir_sensors at about 40 Hz
    CommandResult counter = aseba({ "vars", "counter" });
    ASSERT_EQ(counter.exit_code, 0) << counter.err;
    EXPECT_GT(std::stol(counter.out.substr(counter.out.find('=') + 1)), 0) << counter.out;

    CommandResult emit = aseba({ "emit", "ping", "40", "2" });
    ASSERT_EQ(emit.exit_code, 0) << emit.err;
    EXPECT_EQ(aseba({ "vars", "sum" }).out, "sum = 42\n");

    ASSERT_EQ(aseba({ "vars", "speed.left=55" }).exit_code, 0);
    EXPECT_EQ(aseba({ "vars", "speed.left" }).out, "speed.left = 55\n");
    EXPECT_EQ(aseba({ "stop" }).out, "e-puck0 1: stopped\n");
    EXPECT_TRUE(relay.running()) << "asebaswitch ended";
    EXPECT_TRUE(playground.running()) << "asebaplayground ended";
}
