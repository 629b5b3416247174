// The host board's simulated peripherals: timers and ADC scans fired at the
// right simulated times, the flat world, pins and edges, EEPROM and flash
// with NOR erase-before-write rules, power cuts and saving to a file.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>
#include <memory>
#include <string>
#include <vector>

extern "C" {
#include "boards/epuck_host/host_board.h"
}

namespace
{

constexpr double FCY = 7372800.0 * 8 / 4; // fact sheet §1.6

// The simulated chip counts the e-puck's instruction cycles.
TEST(HostTarget, SimulatedTimeRunsAtTheEpucksInstructionClock)
{
    EXPECT_EQ(double(HOST_CYCLES_PER_SECOND), FCY);
}

struct HostBoard : ::testing::Test {
    std::unique_ptr<hal_board> board = std::make_unique<hal_board>();
    void SetUp() override
    {
        host_board_init(board.get(), nullptr, nullptr);
    }
};

// What a callback saw: which timer, at which cycle.
struct Firing {
    int which;
    uint64_t cycle;
};
struct Recorder {
    hal_board *board;
    std::vector<Firing> firings;
};
struct Tag {
    Recorder *recorder;
    int which;
};
void record(void *context)
{
    auto *tag = static_cast<Tag *>(context);
    tag->recorder->firings.push_back({ tag->which, host_board_cycles(tag->recorder->board) });
}

TEST_F(HostBoard, TimerFiresEveryPeriodAtTheRightCycle)
{
    Recorder recorder{ board.get(), {} };
    Tag agenda{ &recorder, 0 };
    ASSERT_TRUE(epuck_board_timer_start(board.get(), EPUCK_TIMER_SPARE, 100, record, &agenda));
    host_board_advance(board.get(), uint64_t(FCY)); // one second
    // 100 µs is 1474.56 cycles, rounded to 1475 per period as the chip's
    // PR2 = 1474 does (§3.13): 9997 periods fit in a second.
    double period = std::round(100e-6 * FCY);
    ASSERT_EQ(recorder.firings.size(), size_t(std::floor(FCY / period)));
    for (size_t k = 0; k < recorder.firings.size(); k += 997)
        EXPECT_EQ(recorder.firings[k].cycle, uint64_t((k + 1) * period)) << k;
    epuck_board_timer_stop(board.get(), EPUCK_TIMER_SPARE);
    size_t fired = recorder.firings.size();
    host_board_advance(board.get(), uint64_t(FCY));
    EXPECT_EQ(recorder.firings.size(), fired);
}

TEST_F(HostBoard, TimersInterleaveInTimeOrder)
{
    Recorder recorder{ board.get(), {} };
    Tag left{ &recorder, 1 }, right{ &recorder, 2 };
    ASSERT_TRUE(epuck_board_timer_start(board.get(), EPUCK_TIMER_MOTOR_LEFT, 3000, record, &left));
    ASSERT_TRUE(
      epuck_board_timer_start(board.get(), EPUCK_TIMER_MOTOR_RIGHT, 2000, record, &right));
    // Advance in uneven slices; the order must not depend on them.
    for (int i = 0; i < 7; i++)
        host_board_advance(board.get(), uint64_t(FCY * 0.0017));
    // Expected: multiples of each period in whole cycles, merged; at equal
    // times the left motor's timer (earlier in epuck_timer) first.
    const uint64_t end = uint64_t(FCY * 0.0017) * 7;
    std::vector<std::pair<uint64_t, int>> expected;
    for (auto [which, seconds] : { std::pair{ 1, 3e-3 }, std::pair{ 2, 2e-3 } }) {
        uint64_t period = uint64_t(std::llround(seconds * FCY));
        for (uint64_t t = period; t <= end; t += period)
            expected.push_back({ t, which });
    }
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(recorder.firings.size(), expected.size());
    for (size_t i = 0; i < expected.size(); i++) {
        EXPECT_EQ(recorder.firings[i].which, expected[i].second) << i;
        EXPECT_EQ(recorder.firings[i].cycle, expected[i].first) << i;
    }
}

TEST_F(HostBoard, TimerRejectsPeriodsOutOfRange)
{
    EXPECT_FALSE(epuck_board_timer_start(board.get(), EPUCK_TIMER_SPARE, 0, record, nullptr));
    EXPECT_FALSE(epuck_board_timer_start(board.get(), EPUCK_TIMER_SPARE, 2000000, record, nullptr));
    EXPECT_FALSE(epuck_board_timer_start(board.get(), EPUCK_TIMER_COUNT, 1000, record, nullptr));
}

TEST_F(HostBoard, MillisecondsFollowTheSimulatedClock)
{
    host_board_set_time(board.get(), 250);
    EXPECT_EQ(hal_milliseconds(board.get()), 250u);
    EXPECT_NEAR(double(host_board_cycles(board.get())), 0.25 * FCY, 1.0);
    host_board_set_time(board.get(), 100); // never backwards
    EXPECT_EQ(hal_milliseconds(board.get()), 250u);
    host_board_advance(board.get(), uint64_t(FCY / 2));
    EXPECT_EQ(hal_milliseconds(board.get()), 750u);
}

TEST_F(HostBoard, SetTimeFiresDueTimers)
{
    Recorder recorder{ board.get(), {} };
    Tag tick{ &recorder, 0 };
    ASSERT_TRUE(epuck_board_timer_start(board.get(), EPUCK_TIMER_SPARE, 1000, record, &tick));
    host_board_set_time(board.get(), 10);
    // 1 ms is 14745.6 cycles, 14746 per period: 9 periods end before 10 ms.
    EXPECT_EQ(recorder.firings.size(), size_t(std::floor(0.010 * FCY / std::round(1e-3 * FCY))));
    EXPECT_EQ(recorder.firings.size(), 9u);
}

struct Scans {
    int count = 0;
    std::vector<uint16_t> last;
};
void keep_scan(void *context, const uint16_t *values, uint8_t count)
{
    auto *scans = static_cast<Scans *>(context);
    scans->count++;
    scans->last.assign(values, values + count);
}

TEST_F(HostBoard, AdcScansRunAt16384HzWithFlatWorldValues)
{
    Scans scans;
    ASSERT_TRUE(epuck_board_adc_scan_start(board.get(), 0x00FC, keep_scan, &scans));
    host_board_advance(board.get(), uint64_t(FCY));
    EXPECT_EQ(scans.count, 16384);
    // Mics at mid-scale, accelerometer X/Y at zero g, Z at one g (§3.3, §3.4).
    EXPECT_EQ(scans.last, (std::vector<uint16_t>{ 2048, 2048, 2048, 2048, 2048, 2048 + 768 }));
    EXPECT_EQ(epuck_board_adc_read(board.get(), 2), 0); // no single reads while scanning
    ASSERT_TRUE(epuck_board_adc_scan_select(board.get(), 0x1100 | 0x001C));
    host_board_advance(board.get(), uint64_t(FCY / 16384) + 1);
    EXPECT_EQ(scans.last.size(), 5u);
    EXPECT_FALSE(epuck_board_adc_scan_select(board.get(), 0x0100));
    epuck_board_adc_scan_stop(board.get());
    int before = scans.count;
    host_board_advance(board.get(), uint64_t(FCY / 100));
    EXPECT_EQ(scans.count, before);
    EXPECT_EQ(epuck_board_adc_read(board.get(), EPUCK_ADC_ACCELEROMETER_Z), 2048 + 768);
}

// A run of scans the world holds steady (the flat world's) goes to the
// firmware at once, before the timers due during it; each timer still sees
// its own cycle.
struct Runs {
    hal_board *board;
    std::vector<std::pair<uint64_t, uint16_t>> offered; // cycle, scans
};
uint16_t take_run(void *context, const uint16_t *, uint8_t, uint16_t scans)
{
    auto *runs = static_cast<Runs *>(context);
    runs->offered.push_back({ host_board_cycles(runs->board), scans });
    return scans;
}

TEST_F(HostBoard, SteadyScanRunsGoBeforeTheTimersDueDuringThem)
{
    Runs runs{ board.get(), {} };
    Recorder recorder{ board.get(), {} };
    Tag agenda{ &recorder, 0 };
    ASSERT_TRUE(epuck_board_adc_scan_start(board.get(), 0x001C, keep_scan, &runs));
    epuck_board_adc_scan_runs(board.get(), take_run);
    ASSERT_TRUE(epuck_board_timer_start(board.get(), EPUCK_TIMER_SPARE, 100, record, &agenda));
    const uint64_t millisecond = uint64_t(FCY / 1000);
    const uint64_t scan_period = uint64_t(FCY / 16384);
    const uint64_t timer_period = uint64_t(std::round(100e-6 * FCY));
    host_board_advance(board.get(), millisecond);
    // Every scan of the millisecond in one run, from the first scan's cycle.
    ASSERT_EQ(runs.offered.size(), 1u);
    EXPECT_EQ(runs.offered[0].first, scan_period);
    EXPECT_EQ(runs.offered[0].second, millisecond / scan_period);
    ASSERT_EQ(recorder.firings.size(), millisecond / timer_period);
    for (size_t k = 0; k < recorder.firings.size(); k++)
        EXPECT_EQ(recorder.firings[k].cycle, (k + 1) * timer_period) << k;
    EXPECT_EQ(host_board_cycles(board.get()), millisecond);
}

TEST_F(HostBoard, FlatWorldInputsAreNeutral)
{
    for (int bit = 0; bit < 4; bit++)
        EXPECT_FALSE(epuck_board_pin_read(board.get(), epuck_pin(EPUCK_PIN_SELECTOR_0 + bit)));
    EXPECT_TRUE(epuck_board_pin_read(board.get(), EPUCK_PIN_BATTERY_LOW)); // high = battery fine
    EXPECT_TRUE(epuck_board_pin_read(board.get(), EPUCK_PIN_REMOTE));      // receiver idles high
    uint8_t bytes[2] = { 1, 1 };
    EXPECT_FALSE(epuck_board_i2c_read(board.get(), EPUCK_I2C_CAMERA_ADDRESS, 0, bytes, 2));
    epuck_board_camera_start(board.get(), 0, bytes, 1); // one pixel, 2 bytes
    EXPECT_EQ(epuck_board_camera_step(board.get()), EPUCK_CAMERA_DONE);
    EXPECT_EQ(bytes[0], 0);
    // A step with no read started fails.
    EXPECT_EQ(epuck_board_camera_step(board.get()), EPUCK_CAMERA_FAILED);
}

// A world that records outputs and has a remote line the test moves.
struct TestWorld {
    host_world table{};
    bool remote = true;
    std::vector<std::pair<epuck_pin, bool>> written;
    TestWorld()
    {
        table = *host_world_flat();
        table.context = this;
        table.pin_read = [](void *context, epuck_pin pin, uint64_t) {
            return pin == EPUCK_PIN_REMOTE ? static_cast<TestWorld *>(context)->remote : false;
        };
        table.pin_written = [](void *context, epuck_pin pin, bool high, uint64_t) {
            static_cast<TestWorld *>(context)->written.push_back({ pin, high });
        };
    }
};

TEST_F(HostBoard, OutputsReachTheWorldAndEdgesComeBack)
{
    TestWorld world;
    host_board_set_world(board.get(), &world.table);
    epuck_board_pin_write(board.get(), EPUCK_PIN_MOTOR_LEFT_B, true);
    epuck_board_pin_write(board.get(), EPUCK_PIN_SELECTOR_1, true); // an input: ignored
    ASSERT_EQ(world.written.size(), 1u);
    EXPECT_EQ(world.written[0].first, EPUCK_PIN_MOTOR_LEFT_B);
    EXPECT_TRUE(epuck_board_pin_read(board.get(), EPUCK_PIN_MOTOR_LEFT_B));

    int edges = 0;
    auto count = [](void *context) { ++*static_cast<int *>(context); };
    EXPECT_FALSE(
      epuck_board_pin_watch_falling_edge(board.get(), EPUCK_PIN_SELECTOR_0, count, &edges));
    ASSERT_TRUE(epuck_board_pin_watch_falling_edge(board.get(), EPUCK_PIN_REMOTE, count, &edges));
    world.remote = false;
    host_board_input_changed(board.get(), EPUCK_PIN_REMOTE);
    EXPECT_EQ(edges, 1);
    world.remote = true; // a rising edge is not signalled
    host_board_input_changed(board.get(), EPUCK_PIN_REMOTE);
    EXPECT_EQ(edges, 1);
    epuck_board_pin_unwatch(board.get(), EPUCK_PIN_REMOTE);
    world.remote = false;
    host_board_input_changed(board.get(), EPUCK_PIN_REMOTE);
    EXPECT_EQ(edges, 1);
}

TEST_F(HostBoard, EepromBitsOnlyFallUntilErased)
{
    EXPECT_EQ(HOST_EEPROM_WORDS, 2048u); // §1.1: 4096 bytes
    EXPECT_EQ(host_board_eeprom_read(board.get(), 2047), 0xFFFF);
    ASSERT_TRUE(host_board_eeprom_write_word(board.get(), 10, 0x1234));
    EXPECT_EQ(host_board_eeprom_read(board.get(), 10), 0x1234);
    ASSERT_TRUE(host_board_eeprom_write_word(board.get(), 10, 0xFFFF)); // cannot set bits
    EXPECT_EQ(host_board_eeprom_read(board.get(), 10), 0x1234);
    ASSERT_TRUE(host_board_eeprom_write_word(board.get(), 10, 0x0F0F));
    EXPECT_EQ(host_board_eeprom_read(board.get(), 10), 0x1234 & 0x0F0F);
    ASSERT_TRUE(host_board_eeprom_erase_word(board.get(), 10));
    EXPECT_EQ(host_board_eeprom_read(board.get(), 10), 0xFFFF);
    EXPECT_FALSE(host_board_eeprom_erase_word(board.get(), 2048));
}

TEST_F(HostBoard, FlashRowsAreErasedAndProgrammedWhole)
{
    EXPECT_EQ(HAL_FLASH_PROGRAM_WORDS, 32u); // §1.3: a row
    EXPECT_EQ(HAL_FLASH_WORD_SPAN, 2u);      // PC units per instruction
    EXPECT_EQ(HAL_FLASH_END, 0x018000u);     // last word 0x017FFE
    uint32_t unit_start = 0;
    EXPECT_EQ(hal_flash_unit(board.get(), 0x017EE4, &unit_start), 0x40u); // a row
    EXPECT_EQ(unit_start, 0x017EC0u);
    EXPECT_EQ(hal_flash_unit(board.get(), 0x018000, &unit_start), 0u);
    const uint32_t row = 0x017EC0;
    std::vector<uint32_t> first(32), second(32);
    for (uint32_t i = 0; i < 32; i++) {
        first[i] = 0xFF0000u | i;
        second[i] = 0x00FFFFu;
    }
    EXPECT_EQ(hal_flash_read(board.get(), row), 0xFFFFFFu);
    ASSERT_TRUE(hal_flash_program(board.get(), row, first.data(), 32));
    EXPECT_EQ(hal_flash_read(board.get(), row + 2 * 5), 0xFF0005u);
    ASSERT_TRUE(hal_flash_program(board.get(), row, second.data(), 32)); // AND, not replace
    EXPECT_EQ(hal_flash_read(board.get(), row + 2 * 5), 0x000005u);
    ASSERT_TRUE(hal_flash_erase(board.get(), row));
    for (uint32_t i = 0; i < 32; i++)
        EXPECT_EQ(hal_flash_read(board.get(), row + 2 * i), 0xFFFFFFu);
    EXPECT_FALSE(hal_flash_erase(board.get(), row + 0x20));
    EXPECT_FALSE(hal_flash_program(board.get(), 0x018000, first.data(), 32));
    EXPECT_FALSE(hal_flash_program(board.get(), row, first.data(), 31)); // not a whole row
    std::vector<uint32_t> two_rows(64, 0);
    EXPECT_FALSE(hal_flash_program(board.get(), 0x017FC0, two_rows.data(), 64)); // past the end
    EXPECT_EQ(hal_flash_read(board.get(), row + 1), 0u);                         // odd address
}

TEST_F(HostBoard, PowerCutTearsTheInterruptedOperationAndStopsTheRest)
{
    const uint32_t row = 0x004000;
    std::vector<uint32_t> zeros(32, 0);
    host_board_cut_power_at(board.get(), 2);
    ASSERT_TRUE(host_board_eeprom_write_word(board.get(), 0, 0));        // operation 1
    EXPECT_FALSE(hal_flash_program(board.get(), row, zeros.data(), 32)); // 2: cut
    for (uint32_t i = 0; i < 32; i++)
        EXPECT_EQ(hal_flash_read(board.get(), row + 2 * i), i < 16 ? 0u : 0xFFFFFFu) << i;
    EXPECT_FALSE(host_board_eeprom_erase_word(board.get(), 0)); // still off
    EXPECT_EQ(host_board_eeprom_read(board.get(), 0), 0);
    host_board_restore_power(board.get());
    ASSERT_TRUE(hal_flash_erase(board.get(), row));
    EXPECT_EQ(hal_flash_read(board.get(), row), 0xFFFFFFu);
}

TEST_F(HostBoard, PowerCutDuringEraseLeavesHalfTheRow)
{
    const uint32_t row = 0x000100;
    std::vector<uint32_t> zeros(32, 0);
    ASSERT_TRUE(hal_flash_program(board.get(), row, zeros.data(), 32));
    host_board_cut_power_at(board.get(), 1);
    EXPECT_FALSE(hal_flash_erase(board.get(), row));
    EXPECT_EQ(hal_flash_read(board.get(), row), 0xFFFFFFu);
    EXPECT_EQ(hal_flash_read(board.get(), row + 2 * 31), 0u);
}

TEST_F(HostBoard, MemorySurvivesSaveAndLoad)
{
    std::string path = (std::filesystem::temp_directory_path() /
                        ("hal_host_test_" + std::to_string(::getpid()) + ".mem"))
                         .string();
    std::vector<uint32_t> row(32, 0x123456);
    ASSERT_TRUE(hal_flash_program(board.get(), 0x000400, row.data(), 32));
    ASSERT_TRUE(host_board_eeprom_write_word(board.get(), 2047, 0xFFF7));
    ASSERT_TRUE(host_board_save_memory(board.get(), path.c_str()));
    auto other = std::make_unique<hal_board>();
    host_board_init(other.get(), nullptr, nullptr);
    ASSERT_TRUE(host_board_load_memory(other.get(), path.c_str()));
    EXPECT_EQ(hal_flash_read(other.get(), 0x000400 + 2 * 31), 0x123456u);
    EXPECT_EQ(host_board_eeprom_read(other.get(), 2047), 0xFFF7);
    EXPECT_EQ(host_board_eeprom_read(other.get(), 0), 0xFFFF);
    std::FILE *file = std::fopen(path.c_str(), "wb");
    std::fputs("short", file);
    std::fclose(file);
    EXPECT_FALSE(host_board_load_memory(other.get(), path.c_str()));
    std::remove(path.c_str());
    EXPECT_FALSE(host_board_load_memory(other.get(), path.c_str()));
}

TEST_F(HostBoard, LinkAndResetKeepTheirMeaning)
{
    const uint8_t bytes[] = { 1, 2, 3 };
    ASSERT_TRUE(host_board_link_deliver(board.get(), bytes, 3));
    uint8_t got[4];
    EXPECT_EQ(hal_link_receive(board.get(), got, 4), 3);
    EXPECT_EQ(got[2], 3);
    EXPECT_GE(HAL_LINK_RECEIVE_CAPACITY, 522u); // a whole frame (protocol.md §2)
    EXPECT_EQ(hal_link_send_room(board.get()), HAL_LINK_TRANSMIT_CAPACITY);
    EXPECT_FALSE(host_board_take_reset(board.get()));
    hal_reset(board.get());
    EXPECT_TRUE(host_board_take_reset(board.get()));
    EXPECT_FALSE(host_board_take_reset(board.get()));
}

} // namespace
