// `aseba` against a reference node: an e-puck of Debian's asebaplayground
// (headless), behind Debian's asebaswitch (the playground serves one client
// at a time, and each console command is a new client).

#include <gtest/gtest.h>

#include <thread>

#include "console_support.hpp"

using namespace console_test;

namespace
{

bool contains(const std::string &text, const std::string &part)
{
    return text.find(part) != std::string::npos;
}

} // namespace

TEST(ReferencePlayground, ConsoleDrivesAPlaygroundEpuck)
{
    ScratchFolder scratch;
    PlaygroundBehindSwitch reference;
    const std::string &target = reference.target();
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
    EXPECT_TRUE(reference.running()) << "asebaplayground or asebaswitch ended";
}
