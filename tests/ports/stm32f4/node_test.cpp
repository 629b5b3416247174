// The e-puck firmware on the emulated STM32F4 (`make stm32f4`, QEMU's
// netduinoplus2) as users reach it: the project's console and the Debian
// Aseba tools talk to it over its serial port, one client at a time, as to
// a robot over Bluetooth. Each test boots a fresh machine.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include "tests/interop/interop_support.hpp"
#include "tests/ports/stm32f4/qemu_machine.hpp"

namespace
{

using qemu_test::QemuMachine;

constexpr interop::Milliseconds command_timeout{ 30000 };

struct Outcome {
    int status = -1;    // exit status, -1 when killed or out of time
    std::string output; // stdout and stderr
};

class QemuNode : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        // The console remembers its last load in this test's folder only;
        // ASan's leak report is the console tests' business.
        ::setenv("XDG_STATE_HOME", folder.file("state").c_str(), 1);
        ::setenv("ASAN_OPTIONS", "detect_leaks=0", 1);
        machine = std::make_unique<QemuMachine>(QEMU_NODE_IMAGE);
        wait_until_the_node_answers();
    }

    // The board starts at once: what reaches it before its USART is on is
    // lost. Asks LIST_NODES (protocol.md §5) until NODE_PRESENT comes back,
    // each time after a silence longer than the node's 500 ms inter-byte
    // time-out, so that a frame cut by the boot is forgotten (vm/node.h).
    void wait_until_the_node_answers()
    {
        const uint8_t list_nodes[] = { 0x02, 0x00, 0x00, 0x00, 0x11, 0xA0, 0x05, 0x00 };
        const uint8_t node_present[] = { 0x02, 0x00, 0x01, 0x00, 0x0C, 0x90, 0x05, 0x00 };
        int socket = machine->connect();
        for (int attempt = 0; attempt < 15; attempt++) {
            qemu_test::write_all(socket, list_nodes, sizeof list_nodes);
            uint8_t answer[sizeof node_present];
            try {
                qemu_test::read_exactly(socket, answer, sizeof answer, 700);
            } catch (const std::exception &) {
                continue; // lost: ask again
            }
            if (std::equal(answer, answer + sizeof answer, node_present)) {
                ::close(socket);
                return;
            }
        }
        ::close(socket);
        FAIL() << "the node on QEMU never answered LIST_NODES";
    }

    void TearDown() override
    {
        machine.reset();
        std::filesystem::remove_all(folder.file("state")); // the folder takes only files
    }

    Outcome run(const std::vector<std::string> &arguments)
    {
        interop::ToolRun run = interop::run_tool(folder, "command.log", arguments, command_timeout);
        return { run.finished_in_time && run.exit_code ? *run.exit_code : -1,
                 run.output + (run.finished_in_time ? "" : "\n(" + run.how_it_ended + ")") };
    }

    // The console on the machine.
    Outcome aseba(std::vector<std::string> arguments)
    {
        arguments.insert(arguments.begin(),
                         { ASEBA_CONSOLE, "-t", machine->target(), "--timeout", "3000" });
        return run(arguments);
    }

    std::string write_file(const std::string &name, const std::string &text)
    {
        std::string path = folder.file(name);
        std::ofstream(path) << text;
        return path;
    }

    // An .aesl project for the e-puck with `script` and the global events.
    std::string project(const std::string &script, const std::string &events = "")
    {
        return write_file("program.aesl",
                          "<!DOCTYPE aesl-source>\n<network>\n" + events +
                            "<node name=\"e-puck\" nodeId=\"1\">" + script +
                            "</node>\n</network>\n");
    }

    interop::ScratchFolder folder;
    std::unique_ptr<QemuMachine> machine;
};

// Whether `output` has a line that contains `text`.
::testing::AssertionResult has_line(const Outcome &outcome, const std::string &text)
{
    if (outcome.output.find(text) != std::string::npos)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "no \"" << text << "\" in (status " << outcome.status << "):\n"
           << outcome.output;
}

TEST_F(QemuNode, TheConsoleDiscoversAnEpuck)
{
    Outcome nodes = aseba({ "nodes" });
    EXPECT_EQ(nodes.status, 0) << nodes.output;
    // The e-puck's description (robots/epuck/epuck_description.h), as epuck-emu's
    // robots give it (README.md).
    EXPECT_TRUE(has_line(nodes,
                         "node 1 \"e-puck\" on " + machine->target() +
                           ": protocol 5, bytecode 1024 words, stack 32, variables 605 words (23 "
                           "named), 4 local events, 37 native functions; running"));
}

TEST_F(QemuNode, AsebamassloaderLoadsAProgramWhoseVariablesReadBack)
{
    std::string file = project("var answer = 6 * 7\nvar series[3] = [1, 2, 3]\n");
    Outcome loader = run({ "asebamassloader", "--once", file, machine->target() });
    EXPECT_EQ(loader.status, 0) << loader.output;
    EXPECT_TRUE(has_line(loader, "bytecodes loaded to target e-puck"));

    Outcome vars = aseba({ "--program", file, "vars", "answer", "series" });
    EXPECT_EQ(vars.status, 0) << vars.output;
    EXPECT_TRUE(has_line(vars, "answer = 42"));
    EXPECT_TRUE(has_line(vars, "series = 1 2 3"));
}

TEST_F(QemuNode, VariablesWrittenReadBack)
{
    std::string file = project("var table[4]\n");
    ASSERT_EQ(aseba({ "load", file }).status, 0);
    Outcome write = aseba({ "--program", file, "vars", "table=-5,0,32767,-32768" });
    EXPECT_EQ(write.status, 0) << write.output;
    Outcome read = aseba({ "--program", file, "vars", "table", "id" });
    EXPECT_TRUE(has_line(read, "table = -5 0 32767 -32768"));
    EXPECT_TRUE(has_line(read, "id = 1"));
}

// A host's event reaches the program, and the program's reaches the host.
TEST_F(QemuNode, EventsFlowBothWays)
{
    std::string file =
      project("var received = 0\n"
              "timer.period = 50\n"
              "onevent ping\n"
              "\treceived = args[0]\n"
              "onevent timer\n"
              "\tif received != 0 then\n"
              "\t\temit pong received + 1\n"
              "\tend\n",
              "<event size=\"1\" name=\"ping\"/>\n<event size=\"1\" name=\"pong\"/>\n");
    ASSERT_EQ(aseba({ "load", file }).status, 0);
    Outcome emit = aseba({ "--program", file, "emit", "ping", "41" });
    EXPECT_EQ(emit.status, 0) << emit.output;
    EXPECT_TRUE(has_line(aseba({ "--program", file, "vars", "received" }), "received = 41"));
    Outcome monitor =
      aseba({ "--program", file, "monitor", "--event", "pong", "--count", "1", "--duration", "5" });
    EXPECT_EQ(monitor.status, 0) << monitor.output;
    EXPECT_TRUE(has_line(monitor, "pong"));
    EXPECT_TRUE(has_line(monitor, "42"));
}

TEST_F(QemuNode, BreakpointsStopAndStepsAdvance)
{
    // A bare script: line numbers are the script's.
    std::string file = write_file("program.aseba",
                                  "var ticks = 0\n"           // 1
                                  "var doubled = 0\n"         // 2
                                  "timer.period = 20\n"       // 3
                                  "onevent timer\n"           // 4
                                  "\tticks = ticks + 1\n"     // 5
                                  "\tdoubled = ticks * 2\n"); // 6
    ASSERT_EQ(aseba({ "load", file }).status, 0);
    Outcome hit = aseba({ "--program", file, "break", "set", "6", "--wait" });
    EXPECT_EQ(hit.status, 0) << hit.output;
    EXPECT_TRUE(has_line(hit, "breakpoint set at line 6"));
    EXPECT_TRUE(has_line(hit, "breakpoint hit at pc"));
    EXPECT_TRUE(has_line(hit, "line 6: \tdoubled = ticks * 2"));

    // Stopped before line 6: doubled still lags behind ticks.
    Outcome before = aseba({ "--program", file, "vars", "ticks", "doubled" });
    int ticks = std::atoi(before.output.substr(before.output.find("ticks = ") + 8).c_str());
    EXPECT_GE(ticks, 1) << before.output;
    EXPECT_TRUE(has_line(before, "doubled = " + std::to_string(2 * (ticks - 1))));

    Outcome step = aseba({ "--program", file, "step", "--line" });
    EXPECT_EQ(step.status, 0) << step.output;
    EXPECT_TRUE(has_line(aseba({ "--program", file, "vars", "doubled" }),
                         "doubled = " + std::to_string(2 * ticks)));

    ASSERT_EQ(aseba({ "--program", file, "break", "clear", "all" }).status, 0);
    ASSERT_EQ(aseba({ "--program", file, "run" }).status, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    Outcome later = aseba({ "--program", file, "vars", "ticks" });
    int later_ticks = std::atoi(later.output.substr(later.output.find("ticks = ") + 8).c_str());
    EXPECT_GT(later_ticks, ticks + 5) << later.output; // runs on: 20 ms a tick
}

// The paper's controller (annex A) on sensor values a test writes: the
// board has no sensors, its ir_sensors event comes at the e-puck's rate.
TEST_F(QemuNode, ThePapersControllerRunsOnFedSensorValues)
{
    std::string file = "examples/paper-annex.aesl";
    Outcome load = aseba({ "load", file });
    ASSERT_EQ(load.status, 0) << load.output;
    EXPECT_TRUE(has_line(aseba({ "--program", file, "vars", "camLine" }), "camLine = 32"));

    // No shock, a dark camera (no colour), obstacles at the front sensors:
    // part F steers by leftSpeed = 1000 - prox[1] * 4 - prox[0] * 2 and
    // rightSpeed = 1000 - prox[6] * 4 - prox[7] * 2.
    Outcome write = aseba({ "--program", file, "vars", "prox=10,20,0,0,0,0,30,40" });
    ASSERT_EQ(write.status, 0) << write.output;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    Outcome speeds = aseba({ "--program", file, "vars", "leftSpeed", "rightSpeed" });
    EXPECT_TRUE(has_line(speeds, "leftSpeed = 900"));
    EXPECT_TRUE(has_line(speeds, "rightSpeed = 800"));

    // A shock (acc beyond 1000) while the camera sees red: the robot marks red
    // as bad, tells the others (emit bad 0) and turns away.
    // Mean colour (100 + 20 + 20) / 3 = 46 > 38, red the strongest.
    ASSERT_EQ(
      aseba({ "--program", file, "vars", "camR=100", "camG=20", "camB=20", "acc=0,1200,0" }).status,
      0);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    Outcome bad = aseba({ "--program", file, "vars", "badness", "leftSpeed", "rightSpeed" });
    EXPECT_TRUE(has_line(bad, "leftSpeed = -400"));
    EXPECT_TRUE(has_line(bad, "rightSpeed = 400"));
    int red_badness = std::atoi(bad.output.substr(bad.output.find("badness = ") + 10).c_str());
    EXPECT_GT(red_badness, 1000) << bad.output; // set to 1200, then one less per event
}

// WRITE_BYTECODE keeps the program in the board's storage (the port's flash
// interface; RAM kept across resets on this board): after a REBOOT it runs
// at once, without any host.
TEST_F(QemuNode, AStoredProgramRunsAfterAReboot)
{
    std::string file = project("var boots = 0\nboots = boots + 1\ntimer.period = 10\n"
                               "var ticks = 0\nonevent timer\n\tticks = ticks + 1\n");
    ASSERT_EQ(aseba({ "load", file }).status, 0);
    Outcome save = aseba({ "save" });
    EXPECT_EQ(save.status, 0) << save.output;
    Outcome reboot = aseba({ "reboot" });
    EXPECT_EQ(reboot.status, 0) << reboot.output;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    Outcome vars = aseba({ "--program", file, "vars", "boots", "ticks" });
    EXPECT_TRUE(has_line(vars, "boots = 1"));
    int ticks = std::atoi(vars.output.substr(vars.output.find("ticks = ") + 8).c_str());
    EXPECT_GT(ticks, 5) << vars.output;
}

} // namespace
