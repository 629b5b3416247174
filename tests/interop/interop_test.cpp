// Interoperability of our host e-puck node (epuck-emu) with the reference
// Aseba tools of Debian's `aseba` 1.6.99 (protocol 5): each test starts
// epuck-emu and the tools it needs on loopback, drives the tools as a user
// would (../shared/research/reference-tools.md), and observes the robots
// with an independent protocol client (aseba_client.hpp).
//
// The emulator is taken from $EPUCK_EMU, by default the one of the test's own
// build (build/host-sanitize/bin/epuck-emu under `make test`).

#include "aseba_client.hpp"
#include "interop_support.hpp"
#include "tests/bootloader/test_images.hpp"
#include "tools/compiler/aesl.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "tools/flash/hex_image.hpp"

extern "C" {
#include "bootloader/boot_application.h"
}

#include <map>
#include <thread>

namespace interop
{
namespace
{

using namespace std::chrono_literals;

// --- what the tests expect, from the specifications -----------------------

// The e-puck's named variables (hardware/epuck1.md §6.1, upstream firmware).
const std::vector<NamedVariable> epuck_variables = {
    { 1, "id" },
    { 1, "source" },
    { 32, "args" },
    { 1, "leftSpeed" },
    { 1, "rightSpeed" },
    { 8, "leds" },
    { 8, "prox" },
    { 8, "ambiant" },
    { 3, "acc" },
    { 1, "camLine" },
    { 60, "camR" },
    { 60, "camG" },
    { 60, "camB" },
    // The later additions (§6.1, GCtronic column), after the paper's names.
    { 1, "steps.left" },
    { 1, "steps.right" },
    { 3, "mic" },
    { 1, "sel" },
    { 1, "rc5" },
    { 1, "timer.period" },
    { 1, "battery" },
};
const std::vector<std::string> epuck_local_events = { "ir_sensors", "camera", "timer" };
// The standard natives, in order (language.md §13.1), the e-puck's first.
const std::vector<std::string> standard_natives = {
    "math.copy",   "math.fill",        "math.addscalar",  "math.add",        "math.sub",
    "math.mul",    "math.div",         "math.min",        "math.max",        "math.clamp",
    "math.dot",    "math.stat",        "math.argbounds",  "math.sort",       "math.muldiv",
    "math.atan2",  "math.sin",         "math.cos",        "math.rot2",       "math.sqrt",
    "math.rand",   "deque.size",       "deque.get",       "deque.set",       "deque.insert",
    "deque.erase", "deque.push_front", "deque.push_back", "deque.pop_front", "deque.pop_back",
};
// Then the e-puck's DSP natives (issue: DSP natives), in order.
const std::vector<std::string> dsp_natives = {
    "dsp.fft", "dsp.mag", "dsp.fir", "dsp.iir", "dsp.corr", "dsp.conv", "dsp.peak",
};
// All the e-puck's natives, as it describes them.
std::vector<std::string> epuck_natives()
{
    std::vector<std::string> natives = standard_natives;
    natives.insert(natives.end(), dsp_natives.begin(), dsp_natives.end());
    return natives;
}
constexpr const char *epuck_name = "e-puck";
constexpr uint16_t first_robot = 1;

// ir_sensors fires after each full IR set: 4 pairs of 65 ADC scans at
// 16384 Hz (≈ 63 Hz, hardware/epuck1.md §3.2, §6.2).
constexpr double ir_sensors_per_second = 16384.0 / (4 * 65);
// relay.aesl and group.aesl set timer.period to 100 ms; the tests use it for
// time limits.
constexpr Milliseconds timer_period{ 100 };

// Execution flags (bytecode.md §6).
constexpr uint16_t step_by_step_flag = 0x0002;

// Time limits: generous, for a loaded machine; a passing run is far faster.
constexpr Milliseconds tool_timeout{ 10000 };    // massloader needs about 2 s
constexpr Milliseconds answer_timeout{ 2000 };   // a node's answer to a request
constexpr Milliseconds startup_timeout{ 10000 }; // a tool until it serves
constexpr Milliseconds group_settle_time = 30 * timer_period;

// --- helpers --------------------------------------------------------------

// Loads `program` with `asebamassloader --once` through `target` and checks
// that the tool reports success.
void load_with_massloader(const ScratchFolder &scratch,
                          const std::string &target,
                          const std::string &program)
{
    ToolRun loader = run_tool(scratch,
                              "massloader.log",
                              { "asebamassloader", "--once", program_path(program), target },
                              tool_timeout);
    ASSERT_TRUE(loader.finished_in_time)
      << "asebamassloader " << loader.how_it_ended << "; its output:\n"
      << loader.output;
    EXPECT_EQ(loader.exit_code, 0) << loader.how_it_ended << "\n" << loader.output;
    EXPECT_NE(loader.output.find(std::string("bytecodes loaded to target ") + epuck_name),
              std::string::npos)
      << loader.output;
}

// Checks a description against the e-puck's interface.
void expect_epuck_interface(const NodeDescription &description)
{
    EXPECT_EQ(description.header.name, epuck_name);
    EXPECT_EQ(description.header.protocol_version, protocol_version);
    std::vector<std::pair<std::string, uint16_t>> variables, expected_variables;
    for (const auto &variable : description.variables)
        variables.emplace_back(variable.name, variable.size);
    for (const auto &variable : epuck_variables)
        expected_variables.emplace_back(variable.name, variable.size);
    EXPECT_EQ(variables, expected_variables);
    EXPECT_EQ(description.local_events, epuck_local_events);
    EXPECT_EQ(description.native_functions, epuck_natives());
}

// The description of `node`, checked against the e-puck's interface.
NodeDescription describe_epuck(AsebaClient &client, uint16_t node)
{
    auto description = client.describe(node, answer_timeout);
    if (!description) {
        ADD_FAILURE() << "node " << node << " sent no complete, well-formed description";
        return {};
    }
    expect_epuck_interface(*description);
    return *description;
}

// The address of a named variable, failing the test if it is missing.
uint16_t address_of(const NodeDescription &description, const std::string &name)
{
    auto address = description.address_of(name);
    if (!address)
        ADD_FAILURE() << "the description has no variable " << name;
    return address.value_or(0);
}

// Reads one variable of `node`.
std::optional<int16_t> read_variable(AsebaClient &client, uint16_t node, uint16_t address)
{
    auto values = client.read_variables(node, address, 1, answer_timeout);
    if (!values || values->size() != 1)
        return std::nullopt;
    return values->front();
}

// Reads a variable until it equals `expected` or `timeout` passes; returns
// the last value read.
std::optional<int16_t> poll_variable(AsebaClient &client,
                                     uint16_t node,
                                     uint16_t address,
                                     int16_t expected,
                                     Milliseconds timeout)
{
    auto deadline = Clock::now() + timeout;
    std::optional<int16_t> value;
    do {
        value = read_variable(client, node, address);
        if (value == expected)
            break;
        std::this_thread::sleep_for(20ms);
    } while (Clock::now() < deadline);
    return value;
}

// A frame of the given type and source whose payload is `words`.
std::function<bool(const Frame &)> frame_with_words(uint16_t type,
                                                    uint16_t source,
                                                    std::vector<int16_t> words)
{
    return [=](const Frame &frame) {
        std::vector<uint8_t> payload;
        for (int16_t word : words) {
            payload.push_back(uint8_t(uint16_t(word) & 0xFF));
            payload.push_back(uint8_t(uint16_t(word) >> 8));
        }
        return frame.type == type && frame.source == source && frame.payload == payload;
    };
}

// A user event of the given type and source whose arguments are `words`.
std::function<bool(const Frame &)> user_event(uint16_t type,
                                              uint16_t source,
                                              std::vector<int16_t> words)
{
    return [=](const Frame &frame) {
        return frame.is_user_event() && frame_with_words(type, source, words)(frame);
    };
}

// Any frame of the given type and source.
std::function<bool(const Frame &)> from_node(uint16_t type, uint16_t source)
{
    return [=](const Frame &frame) { return frame.type == type && frame.source == source; };
}

// Text with every run of blanks made one space, for comparing tool output
// whose column alignment is not the point.
std::string squeeze_blanks(const std::string &text)
{
    std::string squeezed;
    for (char c : text) {
        bool blank = c == ' ' || c == '\t';
        if (blank && !squeezed.empty() && squeezed.back() == ' ')
            continue;
        squeezed += blank ? ' ' : c;
    }
    return squeezed;
}

// --- 1. asebamassloader ---------------------------------------------------

TEST(Interop, MassloaderLoadsAProgramThatRuns)
{
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, 1);
    ASSERT_NO_FATAL_FAILURE(load_with_massloader(scratch, robots.target(), "counter.aesl"));

    AsebaClient client(robots.port(), answer_timeout);
    uint16_t left_speed = address_of(describe_epuck(client, first_robot), "leftSpeed");

    // counter.aesl copies a count of ir_sensors events to leftSpeed.
    auto first = read_variable(client, first_robot, left_speed);
    auto first_time = Clock::now();
    std::this_thread::sleep_for(500ms);
    auto second = read_variable(client, first_robot, left_speed);
    auto second_time = Clock::now();
    ASSERT_TRUE(first && second) << "no VARIABLES answer";

    double seconds = std::chrono::duration<double>(second_time - first_time).count();
    double rate = (*second - *first) / seconds;
    EXPECT_GE(rate, 0.6 * ir_sensors_per_second) << *first << " then " << *second;
    EXPECT_LE(rate, 1.25 * ir_sensors_per_second + 2 / seconds) << *first << " then " << *second;
}

// --- 2. asebadump ---------------------------------------------------------

TEST(Interop, AsebadumpDecodesAWholeSession)
{
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, 1);

    // asebadump writes through stdio: make it flush every line, so that its
    // output survives the SIGTERM that ends it.
    std::string dump_log = scratch.file("asebadump.log");
    ChildProcess dump({ "stdbuf", "-oL", "asebadump", robots.target() }, dump_log);
    ASSERT_TRUE(wait_for_text_in_file(dump_log, "connection created", startup_timeout))
      << "asebadump did not connect; its output:\n"
      << read_file(dump_log);

    // Description exchange, upload and run, by the loader.
    ASSERT_NO_FATAL_FAILURE(load_with_massloader(scratch, robots.target(), "errors.aesl"));

    AsebaClient client(robots.port(), answer_timeout);
    NodeDescription description = describe_epuck(client, first_robot);
    // errors.aesl: var table[3], var result; events ping, pong, bad_index,
    // divide in that order.
    const uint16_t table = description.first_user_variable();
    const uint16_t table_size = 3;
    const uint16_t result = table + table_size;
    enum : uint16_t { ping, pong, bad_index, divide };

    // What the client sees, for comparison with asebadump's lines. The
    // session runs in a lambda so that a fatal failure in it still lets the
    // test look at asebadump.
    std::optional<OutOfBounds> bounds;
    std::optional<ExecutionState> running_state;
    std::optional<uint16_t> division_pc;
    const int16_t outside_index = 5;
    auto session = [&] {
        // User events both ways: ping [3, 4] gets pong [7, id].
        client.send(ping, { 3, 4 });
        EXPECT_TRUE(
          client.receive_until(user_event(pong, first_robot, { 7, first_robot }), answer_timeout))
          << "no pong [7, 1]";
        EXPECT_EQ(read_variable(client, first_robot, result), 7);

        // An index out of table[3].
        client.send(bad_index, { outside_index });
        auto bounds_frame = client.receive_until(
          from_node(message::array_access_out_of_bounds, first_robot), answer_timeout);
        ASSERT_TRUE(bounds_frame) << "no ARRAY_ACCESS_OUT_OF_BOUNDS";
        bounds = decode_out_of_bounds(*bounds_frame);
        ASSERT_TRUE(bounds) << "malformed ARRAY_ACCESS_OUT_OF_BOUNDS, payload of "
                            << bounds_frame->payload.size() << " bytes";
        EXPECT_EQ(bounds->size, table_size);
        EXPECT_EQ(bounds->index, outside_index);
        EXPECT_LT(bounds->pc, description.header.bytecode_size);

        // The error stopped the VM; RUN restarts it.
        client.send(message::run, { first_robot });
        auto running = client.receive_until(
          [](const Frame &frame) {
              auto state = decode_execution_state(frame);
              return frame.source == first_robot && state && !(state->flags & step_by_step_flag);
          },
          answer_timeout);
        ASSERT_TRUE(running) << "no EXECUTION_STATE_CHANGED without STEP_BY_STEP after RUN";
        running_state = decode_execution_state(*running);

        client.send(divide, { 0 });
        auto division_frame =
          client.receive_until(from_node(message::division_by_zero, first_robot), answer_timeout);
        ASSERT_TRUE(division_frame) << "no DIVISION_BY_ZERO";
        division_pc = decode_division_by_zero(*division_frame);
        ASSERT_TRUE(division_pc) << "malformed DIVISION_BY_ZERO";
    };
    session();

    // Let asebadump print the last messages, and check it did not abort.
    std::this_thread::sleep_for(300ms);
    ASSERT_TRUE(dump.running()) << "asebadump aborted (" << dump.exit_description()
                                << "); its output:\n"
                                << read_file(dump_log);
    dump.stop();
    std::string output = squeeze_blanks(read_file(dump_log));

    EXPECT_EQ(output.find("overread"), std::string::npos) << output;
    EXPECT_EQ(output.find("not fully deserialized"), std::string::npos) << output;

    std::vector<std::string> expected = {
        "node present from 1 : protocol version 5",
        "description from 1 : Node e-puck using protocol version 5",
        "bytecode: " + std::to_string(description.header.bytecode_size),
        "named variables: " + std::to_string(epuck_variables.size()),
        "local events: " + std::to_string(epuck_local_events.size()),
        "native functions: " + std::to_string(epuck_natives().size()),
        "set bytecode from 0 : dest 1",
        "run from 0 : dest 1",
        "user message from 0 : user message of size 2 : 3 4",
        "user message from 1 : user message of size 2 : 7 1",
        "variables from 1 : start " + std::to_string(result) + ", variables vector of size 1",
        "user message from 0 : user message of size 1 : 5",
    };
    if (bounds)
        expected.push_back("array access out of bounds from 1 : pc " + std::to_string(bounds->pc) +
                           ", size " + std::to_string(table_size) + ", index " +
                           std::to_string(outside_index));
    if (running_state)
        expected.push_back("execution state from 1 : pc " + std::to_string(running_state->pc) +
                           ", flags");
    if (division_pc)
        expected.push_back("division by zero from 1 : pc " + std::to_string(*division_pc));
    for (const auto &variable : epuck_variables)
        expected.push_back("named variable from 1 : " + variable.name + " of size " +
                           std::to_string(variable.size));
    for (const auto &event : epuck_local_events)
        expected.push_back("local event from 1 : " + event + " :");
    for (const auto &native : epuck_natives())
        expected.push_back("native function description from 1 : " + native + " (");
    for (const auto &line : expected)
        EXPECT_NE(output.find(line), std::string::npos) << "missing: " << line;
}

// --- 3. asebacmd ----------------------------------------------------------

TEST(Interop, AsebacmdSendsEventsAndQueries)
{
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, 1);
    ASSERT_NO_FATAL_FAILURE(load_with_massloader(scratch, robots.target(), "store.aesl"));

    AsebaClient client(robots.port(), answer_timeout);
    NodeDescription description = describe_epuck(client, first_robot);
    uint16_t left_speed = address_of(description, "leftSpeed");
    uint16_t right_speed = address_of(description, "rightSpeed");
    auto asebacmd = [&](std::vector<std::string> command) {
        command.insert(command.begin(), { "asebacmd", "-t", robots.target() });
        ToolRun run = run_tool(scratch, "asebacmd.log", command, tool_timeout);
        EXPECT_TRUE(run.finished_in_time && run.exit_code == 0)
          << command[3] << ": " << run.how_it_ended << "\n"
          << run.output;
    };

    // usermsg: event 0 (store) with two arguments, stored by the program
    // (speeds within ±1000: the firmware clamps them, hardware §6.1).
    const int16_t left = 834, right = 567;
    asebacmd({ "usermsg", "0", std::to_string(left), std::to_string(right) });
    EXPECT_TRUE(client.receive_until(user_event(0, host_id, { left, right }), answer_timeout))
      << "the event asebacmd sent did not reach the network";
    EXPECT_EQ(poll_variable(client, first_robot, left_speed, left, answer_timeout), left);
    EXPECT_EQ(read_variable(client, first_robot, right_speed), right);

    // listnodes: the robot answers the tool's LIST_NODES.
    asebacmd({ "listnodes" });
    EXPECT_TRUE(client.receive_until(
      frame_with_words(message::list_nodes, host_id, { protocol_version }), answer_timeout))
      << "no LIST_NODES from asebacmd";
    auto present =
      client.receive_until(from_node(message::node_present, first_robot), answer_timeout);
    ASSERT_TRUE(present) << "no NODE_PRESENT";
    EXPECT_EQ(decode_node_present(*present), protocol_version);

    // getnodedescr: the robot sends its whole description again.
    asebacmd({ "getnodedescr", "1" });
    EXPECT_TRUE(client.receive_until(
      frame_with_words(message::get_node_description, host_id, { first_robot, protocol_version }),
      answer_timeout))
      << "no GET_NODE_DESCRIPTION from asebacmd";
    auto description_again = client.receive_description(first_robot, answer_timeout);
    ASSERT_TRUE(description_again) << "no complete, well-formed description";
    expect_epuck_interface(*description_again);

    // sleep sends SUSPEND_TO_RAM. epuck-emu has no way to be woken, so the
    // robot must stay awake (protocol.md §6.8 lets a node ignore it).
    asebacmd({ "sleep", "1" });
    EXPECT_TRUE(client.receive_until(
      frame_with_words(message::suspend_to_ram, host_id, { first_robot }), answer_timeout))
      << "no SUSPEND_TO_RAM(1) from asebacmd";
    EXPECT_EQ(read_variable(client, first_robot, left_speed), left);
}

// --- 4. asebaswitch -------------------------------------------------------

TEST(Interop, AsebaswitchRelaysTheRobot)
{
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, 1);
    uint16_t switch_port = find_free_port();
    ChildProcess relay({ "asebaswitch", "-p", std::to_string(switch_port), robots.target() },
                       scratch.file("asebaswitch.log"));
    ASSERT_TRUE(wait_until_listening(switch_port, startup_timeout))
      << "asebaswitch does not listen (" << (relay.running() ? "running" : relay.exit_description())
      << "); its output:\n"
      << read_file(scratch.file("asebaswitch.log"));

    // Through the switch only, from here on.
    ASSERT_NO_FATAL_FAILURE(load_with_massloader(scratch, tcp_target(switch_port), "relay.aesl"));
    AsebaClient client(switch_port, answer_timeout);
    NodeDescription description = describe_epuck(client, first_robot);
    uint16_t ticks = description.first_user_variable();
    uint16_t right_speed = address_of(description, "rightSpeed");
    enum : uint16_t { tick, set_speed };

    // Two consecutive emitted ticks: [n, 1] then [n + 1, 1].
    auto is_tick = [](const Frame &frame) {
        return frame.type == tick && frame.source == first_robot;
    };
    auto first = client.receive_until(is_tick, 3 * timer_period + answer_timeout);
    auto second = client.receive_until(is_tick, 3 * timer_period + answer_timeout);
    ASSERT_TRUE(first && second) << "the emitted ticks did not come through the switch";
    auto first_words = decode_user_event(*first);
    auto second_words = decode_user_event(*second);
    ASSERT_TRUE(first_words && second_words && first_words->size() == 2 &&
                second_words->size() == 2)
      << "a tick is not a 2-argument event";
    EXPECT_EQ((*first_words)[1], first_robot);
    EXPECT_EQ((*second_words)[0], (*first_words)[0] + 1);

    // Variables read through the switch.
    auto count = read_variable(client, first_robot, ticks);
    ASSERT_TRUE(count) << "no VARIABLES through the switch";
    EXPECT_GE(*count, (*second_words)[0]);

    // An event sent through the switch.
    const int16_t speed = 77;
    client.send(set_speed, { speed });
    EXPECT_EQ(poll_variable(client, first_robot, right_speed, speed, answer_timeout), speed);
    EXPECT_TRUE(relay.running()) << "asebaswitch ended: " << relay.exit_description();
}

// --- 5. asebahttp ---------------------------------------------------------

TEST(Interop, AsebahttpReadsVariablesAndSendsEvents)
{
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, 1);
    uint16_t http_port = find_free_port();
    uint16_t aseba_port = find_free_port();
    std::string log = scratch.file("asebahttp.log");
    // asebahttp learns the program's names only from a program it loads.
    ChildProcess http({ "asebahttp",
                        "-p",
                        std::to_string(http_port),
                        "-s",
                        std::to_string(aseba_port),
                        "-a",
                        program_path("http.aesl"),
                        robots.target() },
                      log);

    // Ready when it answers a variable of the loaded program.
    const int16_t marker_start = 1234; // var marker = 1234 in http.aesl
    const std::string marker_path = std::string("/nodes/") + epuck_name + "/marker";
    std::optional<HttpResponse> marker;
    auto deadline = Clock::now() + startup_timeout;
    while (Clock::now() < deadline && http.running()) {
        marker = http_request(http_port, "GET", marker_path, answer_timeout);
        if (marker && marker->status == 200)
            break;
        std::this_thread::sleep_for(100ms);
    }
    ASSERT_TRUE(marker && marker->status == 200)
      << "asebahttp never served " << marker_path << " ("
      << (http.running() ? "running" : http.exit_description()) << "); its output:\n"
      << read_file(log);
    EXPECT_EQ(marker->body, "[" + std::to_string(marker_start) + "]");

    // An event with an argument, by POST.
    const int16_t speed = 42;
    auto posted =
      http_request(http_port,
                   "POST",
                   std::string("/nodes/") + epuck_name + "/set_speed/" + std::to_string(speed),
                   answer_timeout);
    ASSERT_TRUE(posted) << "no answer to the POST";
    EXPECT_EQ(posted->status / 100, 2) << posted->status << " " << posted->body;

    // Its effect, seen by our own client...
    AsebaClient client(robots.port(), answer_timeout);
    NodeDescription description = describe_epuck(client, first_robot);
    uint16_t right_speed = address_of(description, "rightSpeed");
    EXPECT_EQ(poll_variable(client, first_robot, right_speed, speed, answer_timeout), speed);
    EXPECT_EQ(read_variable(client, first_robot, description.first_user_variable()),
              marker_start + 1)
      << "marker counts set_speed events";

    // ...and by asebahttp.
    auto read_back = http_request(
      http_port, "GET", std::string("/nodes/") + epuck_name + "/rightSpeed", answer_timeout);
    ASSERT_TRUE(read_back) << "no answer to GET rightSpeed";
    EXPECT_EQ(read_back->status, 200);
    EXPECT_EQ(read_back->body, "[" + std::to_string(speed) + "]");
    EXPECT_TRUE(http.running()) << "asebahttp ended: " << http.exit_description();
}

// --- 6. several robots ----------------------------------------------------

TEST(Interop, RobotsOfAGroupHearEachOther)
{
    const uint16_t robot_count = 3;
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, robot_count);

    // Discovery: one NODE_PRESENT(5) per robot, ids 1..3. The client then
    // stays silent while the loader runs (reference-tools.md, pitfall 9).
    std::map<uint16_t, int> presents;
    {
        AsebaClient client(robots.port(), answer_timeout);
        client.send(message::list_nodes, { int16_t(protocol_version) });
        for (const Frame &frame : client.collect(500ms)) {
            if (frame.type != message::node_present)
                continue;
            EXPECT_EQ(decode_node_present(frame), protocol_version) << "from " << frame.source;
            presents[frame.source]++;
        }
    }
    std::map<uint16_t, int> one_each = { { 1, 1 }, { 2, 1 }, { 3, 1 } };
    EXPECT_EQ(presents, one_each);

    // group.aesl on every robot named e-puck: robot 1 says hello every
    // timer event, the others echo.
    ASSERT_NO_FATAL_FAILURE(load_with_massloader(scratch, robots.target(), "group.aesl"));
    AsebaClient client(robots.port(), answer_timeout);
    NodeDescription description = describe_epuck(client, first_robot);
    const uint16_t heard_from = description.first_user_variable();
    const uint16_t echo_mask = heard_from + 1;

    // What each robot should have heard: the hello of robot 1 (not its own)
    // and the echoes of the others (each robot's id as a bit).
    for (uint16_t robot = 1; robot <= robot_count; robot++) {
        SCOPED_TRACE("robot " + std::to_string(robot));
        int16_t expected_mask = 0;
        for (uint16_t other = 2; other <= robot_count; other++)
            if (other != robot)
                expected_mask = int16_t(expected_mask | (1 << other));
        const int16_t expected_sender = robot == first_robot ? 0 : first_robot;
        // The robots may still be starting: give them some timer periods.
        EXPECT_EQ(poll_variable(client, robot, echo_mask, expected_mask, group_settle_time),
                  expected_mask)
          << "echo_mask";
        EXPECT_EQ(poll_variable(client, robot, heard_from, expected_sender, answer_timeout),
                  expected_sender)
          << "heard_from";
    }
}

// --- 7. asebacmd whex ------------------------------------------------------

// An application image the robots' bootloader accepts (or, with `corrupt`,
// one whose descriptor CRC is off by one bit), written as Microchip HEX.
std::string write_application_image(const ScratchFolder &scratch,
                                    const std::string &name,
                                    bool corrupt)
{
    constexpr uint32_t application_start = BOOT_APPLICATION_START; // the bootloader's first page
    constexpr uint32_t instructions = 300;
    constexpr uint32_t pc_units_per_instruction = 2;
    aseba::flash::ProgramImage image;
    for (uint32_t i = 0; i < instructions; i++)
        image.instructions[application_start + i * pc_units_per_instruction] = 0x123456u ^ i;
    aseba::flash::add_application_descriptor(image, application_start);
    if (corrupt)
        image.instructions[BOOT_DESCRIPTOR_ADDRESS +
                           BOOT_DESCRIPTOR_CRC_INDEX * pc_units_per_instruction] ^= 1;
    std::string path = scratch.file(name);
    std::ofstream(path) << aseba::flash::write_microchip_hex(image);
    return path;
}

// Whether `robot` answers LIST_NODES within `timeout` (an application runs).
bool answers_as_node(AsebaClient &client, uint16_t robot, Milliseconds timeout)
{
    client.send(message::list_nodes, { int16_t(protocol_version) });
    return client.receive_until(from_node(message::node_present, robot), timeout).has_value();
}

// `asebacmd whex ROBOT FILE reset`, which must report the write complete.
void flash_with_asebacmd(const ScratchFolder &scratch,
                         const EmulatedRobots &robots,
                         uint16_t robot,
                         const std::string &file)
{
    ToolRun run =
      run_tool(scratch,
               "asebacmd.log",
               { "asebacmd", "-t", robots.target(), "whex", std::to_string(robot), file, "reset" },
               tool_timeout);
    EXPECT_TRUE(run.finished_in_time && run.exit_code == 0) << run.how_it_ended << "\n"
                                                            << run.output;
    EXPECT_NE(run.output.find("Write completed"), std::string::npos) << run.output;
}

TEST(Interop, AsebacmdWhexFlashesARobotThroughItsBootloader)
{
    const uint16_t robot_count = 2, flashed = 2;
    ScratchFolder scratch;
    EmulatedRobots robots(scratch, robot_count);
    auto whex = [&](const std::string &file) {
        flash_with_asebacmd(scratch, robots, flashed, file);
    };

    // A refused image: every page is acknowledged, but the bootloader finds
    // no valid application after BOOTLOADER_RESET and stays; the robot is no
    // longer a node, the other robot still is.
    whex(write_application_image(scratch, "corrupt.hex", true));
    {
        AsebaClient client(robots.port(), answer_timeout);
        EXPECT_FALSE(answers_as_node(client, flashed, 1500ms));
        EXPECT_TRUE(answers_as_node(client, first_robot, answer_timeout));
    }
    // asebacmd's REBOOT reaches the waiting bootloader, which describes
    // itself again; the good image then starts.
    whex(write_application_image(scratch, "good.hex", false));
    AsebaClient client(robots.port(), answer_timeout);
    EXPECT_TRUE(answers_as_node(client, flashed, answer_timeout));
    EXPECT_TRUE(answers_as_node(client, first_robot, answer_timeout));
}

// The image epuck-image writes for the Aseba bootloader, from XC16-style
// HEX files with unprogrammed words inside the application
// (tests/bootloader/hex/application.hex): asebacmd writes zeros where a
// page has no data and skips pages with none, so written with its gaps the
// image does not match its descriptor's CRC and the robot stays in its
// bootloader; epuck-image writes every word of the pages, and it starts.
TEST(Interop, AsebacmdWhexFlashesTheImageEpuckImageWrites)
{
    const uint16_t robot_count = 2, flashed = 2;
    ScratchFolder scratch;
    std::string bootloader = scratch.file("bootloader.hex");
    std::ofstream(bootloader) << aseba::flash::write_microchip_hex(
      bootloader_test::bootloader_image());
    std::string application = "tests/bootloader/hex/application.hex";
    std::string output = scratch.file("epuck-aseba.hex");
    ToolRun built = run_tool(scratch,
                             "epuck-image.log",
                             { our_program_path("epuck-image"),
                               application,
                               bootloader,
                               output,
                               scratch.file("factory.hex") },
                             tool_timeout);
    ASSERT_TRUE(built.finished_in_time && built.exit_code == 0) << built.how_it_ended << "\n"
                                                                << built.output;
    std::string with_gaps = scratch.file("with-gaps.hex");
    std::ofstream(with_gaps) << aseba::flash::write_microchip_hex(
      bootloader_test::application_image());

    EmulatedRobots robots(scratch, robot_count);
    auto whex = [&](const std::string &file) {
        flash_with_asebacmd(scratch, robots, flashed, file);
    };
    whex(with_gaps);
    {
        AsebaClient client(robots.port(), answer_timeout);
        EXPECT_FALSE(answers_as_node(client, flashed, 1500ms));
    }
    whex(output);
    AsebaClient client(robots.port(), answer_timeout);
    EXPECT_TRUE(answers_as_node(client, flashed, answer_timeout));
    EXPECT_TRUE(answers_as_node(client, first_robot, answer_timeout));
}

// --- 8. .aesl projects our writer wrote ------------------------------------

// A project written by tools/compiler/aesl's writer reads back equal, and
// asebamassloader takes it as its own: each robot gets the program of its
// node id, with the project's constant, and runs it.
TEST(Interop, MassloaderLoadsAProjectOurWriterWrote)
{
    aseba::AeslProject project;
    project.definitions.events = { { "ping", 1 }, { "report", 2 } };
    // Positive: asebamassloader reads constants as unsigned (aesl.md §2.1).
    project.definitions.constants = { { "STEP", 7 } };
    for (uint16_t id = 1; id <= 2; id++) {
        aseba::AeslNode node;
        node.name = epuck_name;
        node.node_id = id;
        node.source = "leftSpeed = " + std::to_string(id) + " * STEP\n" +
                      "timer.period = 10\n"
                      "onevent timer\n"
                      "  if rightSpeed < 1000 then\n"
                      "    rightSpeed = rightSpeed + 1\n"
                      "  end\n"
                      "onevent ping\n"
                      "  emit report [id, args[0]]\n";
        project.nodes.push_back(node);
    }
    ScratchFolder scratch;
    std::string file = scratch.file("written.aesl");
    std::ofstream(file) << aseba::write_aesl(project);

    std::ifstream written(file);
    std::string text((std::istreambuf_iterator<char>(written)), std::istreambuf_iterator<char>());
    aseba::AeslReadResult read = aseba::read_aesl(text);
    ASSERT_TRUE(read.ok) << read.error;
    ASSERT_EQ(read.project.nodes.size(), 2u);
    EXPECT_EQ(read.project.definitions.events.size(), 2u);
    EXPECT_EQ(read.project.definitions.constants.at(0).value, 7);
    for (size_t i = 0; i < 2; i++) {
        EXPECT_EQ(read.project.nodes[i].source, project.nodes[i].source);
        EXPECT_EQ(read.project.nodes[i].node_id, project.nodes[i].node_id);
    }

    EmulatedRobots robots(scratch, 2);
    ToolRun loader = run_tool(scratch,
                              "massloader.log",
                              { "asebamassloader", "--once", file, robots.target() },
                              tool_timeout);
    ASSERT_TRUE(loader.finished_in_time) << loader.how_it_ended << "\n" << loader.output;
    EXPECT_EQ(loader.exit_code, 0) << loader.output;

    AsebaClient client(robots.port(), answer_timeout);
    for (uint16_t id = 1; id <= 2; id++) {
        SCOPED_TRACE("robot " + std::to_string(id));
        NodeDescription description = describe_epuck(client, id);
        EXPECT_EQ(
          poll_variable(
            client, id, address_of(description, "leftSpeed"), int16_t(7 * id), answer_timeout),
          7 * id);
        // Its timer handler runs: rightSpeed climbs.
        uint16_t right_speed = address_of(description, "rightSpeed");
        auto first = read_variable(client, id, right_speed);
        std::this_thread::sleep_for(10 * 10ms);
        auto later = read_variable(client, id, right_speed);
        ASSERT_TRUE(first && later);
        EXPECT_GT(*later, *first);
    }
}

} // namespace
} // namespace interop
