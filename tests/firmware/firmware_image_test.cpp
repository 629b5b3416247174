// The whole firmware image (firmware + drivers + node + VM) on a host board
// in a modelled world: a program compiled for the e-puck reads prox, acc and
// the selector's node id, and sets speeds and LEDs, observed on the motor
// phase lines and LED pins; the `timer` and `ir_sensors` events come at
// their rates.

#include "tests/robots/epuck/modelled_world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "store/bytecode_store.h"
#include "robots/epuck/devices/epuck_devices.h"
#include "robots/epuck/devices/epuck_selector.h"
#include "firmware/firmware.h"
}

namespace drivers_test
{
namespace
{

constexpr const char *program = R"(var timer_ticks = 0
var ir_events = 0
timer.period = 10

onevent ir_sensors
	ir_events = ir_events + 1
	leftSpeed = prox[0]
	rightSpeed = acc[2]
	leds[2] = 1

onevent timer
	timer_ticks = timer_ticks + 1
)";

struct FirmwareImage : ::testing::Test {
    std::unique_ptr<hal_board> board = std::make_unique<hal_board>();
    std::unique_ptr<firmware_state> firmware = std::make_unique<firmware_state>();
    std::unique_ptr<robot_devices> devices = std::make_unique<robot_devices>();
    ModelledWorld world;
    uint16_t timer_ticks_address = 0;

    void SetUp() override
    {
        host_board_init(board.get(), nullptr, nullptr);
        world.ambient.fill(3000);
        world.channel.fill(2048);
        world.channel[EPUCK_ADC_ACCELEROMETER_Z] = 2048 + 768; // upright, still
        // Selector at 13: node id (13 & 7) + 1 = 6 (§6.1).
        world.input[EPUCK_PIN_SELECTOR_0] = true;
        world.input[EPUCK_PIN_SELECTOR_2] = true;
        world.input[EPUCK_PIN_SELECTOR_3] = true;
        world.attach(board.get());
        boot();

        aseba::ProgramFile file;
        file.file_name = "image_test.aseba";
        file.source = program;
        std::string error;
        aseba::CompileResult compiled =
          aseba::compile_program_file(file, aseba::epuck_target(), error);
        ASSERT_TRUE(compiled.ok) << error;
        for (const auto &variable : compiled.variables)
            if (variable.name == "timer_ticks")
                timer_ticks_address = variable.address;
        firmware_start_program(
          firmware.get(), compiled.bytecode.data(), uint16_t(compiled.bytecode.size()));
    }
    // Starts the firmware as the robot's entry point does: as the node id
    // the bootloader answered as (the stored settings' or the selector's).
    void boot()
    {
        uint16_t id =
          store_node_id(board.get(), epuck_selector_node_id(epuck_selector_read(board.get())));
        firmware_init(firmware.get(), board.get(), devices.get(), id);
    }
    // Runs the main loop over `seconds` of board time, a pass per 0.5 ms.
    void run_seconds(double seconds)
    {
        const uint64_t step = uint64_t(0.5e-3 * FCY);
        for (double t = 0; t < seconds; t += 0.5e-3) {
            host_board_advance(board.get(), step);
            firmware_poll(firmware.get());
        }
    }
    int16_t variable(uint16_t address) const
    {
        return firmware->variables.words[address];
    }
    // Steps of one motor in the world's record since `from`.
    size_t steps_since(epuck_pin first, uint64_t from) const
    {
        std::vector<uint64_t> cycles;
        for (const PinChange &change : world.changes)
            if (change.pin >= first && change.pin < first + 4 && change.cycle >= from &&
                (cycles.empty() || cycles.back() != change.cycle))
                cycles.push_back(change.cycle);
        return cycles.size();
    }
};

TEST_F(FirmwareImage, NodeIdComesFromTheSelector)
{
    EXPECT_EQ(firmware->variables.named.id[0], 6);
    run_seconds(0.01);
    EXPECT_EQ(firmware->variables.named.selector[0], 13);
    EXPECT_EQ(firmware->variables.named.battery[0], 1);
}

TEST_F(FirmwareImage, ProgramDrivesTheMotorsFromTheSensors)
{
    run_seconds(2.0); // calibration: 100 IR sets at 63 Hz
    EXPECT_EQ(firmware->variables.named.left_speed[0], 0);
    EXPECT_EQ(firmware->variables.named.right_speed[0], 768); // one g on Z (§3.3)
    EXPECT_EQ(firmware->variables.named.acc[2], 768);
    EXPECT_TRUE(world.output[EPUCK_PIN_LED_2]);

    // An obstacle in front of sensor 0: 400 counts of reflection.
    world.reflection[0] = 400;
    run_seconds(0.1);
    EXPECT_EQ(firmware->variables.named.prox[0], 400);
    EXPECT_EQ(firmware->variables.named.left_speed[0], 400);
    uint64_t from = host_board_cycles(board.get());
    int16_t left_before = firmware->variables.named.steps_left[0];
    run_seconds(1.0);
    EXPECT_NEAR(double(steps_since(EPUCK_PIN_MOTOR_LEFT_A, from)), 400.0, 2.0);
    EXPECT_NEAR(double(steps_since(EPUCK_PIN_MOTOR_RIGHT_A, from)), 768.0, 2.0);
    EXPECT_NEAR(double(firmware->variables.named.steps_left[0] - left_before), 400.0, 2.0);
}

TEST_F(FirmwareImage, EventsComeAtTheirRates)
{
    run_seconds(1.0);
    int16_t ticks = variable(timer_ticks_address);
    int16_t ir = variable(uint16_t(timer_ticks_address + 1));
    run_seconds(1.0);
    EXPECT_NEAR(double(variable(timer_ticks_address) - ticks), 100.0, 2.0); // timer.period 10 ms
    EXPECT_NEAR(double(variable(uint16_t(timer_ticks_address + 1)) - ir), 16384.0 / 260, 2.0);
}

} // namespace
} // namespace drivers_test

namespace drivers_test
{
namespace
{

// WRITE_BYTECODE (protocol.md §6.8) stores the running program; after a
// reboot it runs at once, without any host (bytecode.md §6.5).
TEST_F(FirmwareImage, StoredProgramRunsAfterReboot)
{
    // WRITE_BYTECODE to node 6: len 2, source 0, type 0xA00D, dest 6.
    const uint8_t write_bytecode[] = { 0x02, 0x00, 0x00, 0x00, 0x0d, 0xa0, 0x06, 0x00 };
    ASSERT_TRUE(host_board_link_deliver(board.get(), write_bytecode, sizeof write_bytecode));
    run_seconds(0.05);

    // Reboot: a fresh firmware on the same board, whose memories persist.
    firmware = std::make_unique<firmware_state>();
    boot();
    EXPECT_EQ(variable(timer_ticks_address), 0);
    run_seconds(1.0);
    EXPECT_NEAR(double(variable(timer_ticks_address)), 100.0, 2.0); // timer.period 10 ms
}

// WRITE_BYTECODE stores the program without the zeros that end the node's
// bytecode array (a short program then takes one block of flash, not the
// whole slot), and a reboot gives the array back whole, whatever the memory
// held before.
TEST_F(FirmwareImage, StoredProgramLeavesOutTheZerosThatEndIt)
{
    const std::vector<uint16_t> running(firmware->bytecode,
                                        firmware->bytecode + FIRMWARE_BYTECODE_WORDS);
    size_t length = running.size();
    while (length > 1 && running[length - 1] == 0)
        length--;
    ASSERT_LT(length, running.size());
    const uint8_t write_bytecode[] = { 0x02, 0x00, 0x00, 0x00, 0x0d, 0xa0, 0x06, 0x00 };
    ASSERT_TRUE(host_board_link_deliver(board.get(), write_bytecode, sizeof write_bytecode));
    run_seconds(0.05);

    std::vector<uint16_t> stored(FIRMWARE_BYTECODE_WORDS);
    uint16_t count = 0;
    ASSERT_TRUE(store_load_bytecode(board.get(), stored.data(), FIRMWARE_BYTECODE_WORDS, &count));
    EXPECT_EQ(count, length);

    firmware = std::make_unique<firmware_state>();
    std::fill(std::begin(firmware->bytecode), std::end(firmware->bytecode), uint16_t(0xFFFF));
    boot();
    EXPECT_TRUE(std::equal(running.begin(), running.end(), firmware->bytecode));
}

// Without a stored program the robot boots idle.
TEST(FirmwareBoot, NothingStoredNothingRuns)
{
    auto board = std::make_unique<hal_board>();
    auto firmware = std::make_unique<firmware_state>();
    auto devices = std::make_unique<robot_devices>();
    host_board_init(board.get(), nullptr, nullptr);
    firmware_init(firmware.get(), board.get(), devices.get(), 1);
    EXPECT_FALSE(vm_is_event_active(&firmware->node.vm));
    EXPECT_EQ(vm_event_address(&firmware->node.vm, 0xFFFF), 0);
}

} // namespace
} // namespace drivers_test
