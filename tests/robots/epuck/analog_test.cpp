// The analog drivers on the host board's ADC scan: proximity pulse and
// sample timing and calibration (hardware §3.2), accelerometer offsets
// (§3.3), microphone volume and recordings (§3.4), against a modelled
// world.

#include "modelled_world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

extern "C" {
#include "robots/epuck/devices/epuck_analog.h"
}

namespace drivers_test
{
namespace
{

constexpr double scan_rate = 16384.0; // §3.2: the advanced scan's interrupt rate

struct Analog : ::testing::Test {
    std::unique_ptr<hal_board> board = std::make_unique<hal_board>();
    ModelledWorld world;
    epuck_proximity proximity{};
    epuck_accelerometer accelerometer{};
    epuck_microphones microphones{};
    epuck_analog analog{};

    void SetUp() override
    {
        host_board_init(board.get(), nullptr, nullptr);
        world.ambient.fill(3000);
        world.channel.fill(2048);
        world.attach(board.get());
    }
    void start()
    {
        epuck_proximity_init(&proximity, board.get());
        epuck_accelerometer_init(&accelerometer, board.get());
        epuck_microphones_init(&microphones, board.get());
        ASSERT_TRUE(
          epuck_analog_start(&analog, board.get(), &proximity, &accelerometer, &microphones));
    }
    void run_seconds(double seconds)
    {
        host_board_advance(board.get(), uint64_t(std::llround(seconds * FCY)));
    }
    // Counts the full sets reported during `seconds`, taking each as it comes.
    int take_sets_during(double seconds,
                         std::array<int16_t, 8> &prox,
                         std::array<int16_t, 8> &ambient)
    {
        int sets = 0;
        const double step = 1e-3;
        for (double t = 0; t < seconds; t += step) {
            run_seconds(step);
            if (epuck_proximity_take(&proximity, prox.data(), ambient.data()))
                sets++;
        }
        return sets;
    }
};

// Each pair's emitter goes on right after its ambient sample, its lit
// sample comes about 300 µs later with the emitter still on, and the
// emitter goes off with it (§3.2: about 370 µs on).
TEST_F(Analog, EachPairIsPulsedAndSampledAsTheFactSheetTimesIt)
{
    start();
    world.changes.clear(); // the emitters switched off at init
    run_seconds(0.1);
    for (unsigned pair = 0; pair < 4; pair++) {
        SCOPED_TRACE("pair " + std::to_string(pair));
        auto pulses = world.changes_of(epuck_pin(EPUCK_PIN_IR_PULSE_0_4 + pair));
        ASSERT_GE(pulses.size(), 10u);
        for (size_t i = 0; i + 1 < pulses.size(); i += 2) {
            ASSERT_TRUE(pulses[i].high);
            ASSERT_FALSE(pulses[i + 1].high);
            uint64_t on = pulses[i].cycle, off = pulses[i + 1].cycle;
            double on_us = double(off - on) / FCY * 1e6;
            EXPECT_GE(on_us, 300.0);
            EXPECT_LE(on_us, 400.0);
            // The sensors of the pair: an ambient conversion at switch-on
            // (before it), a lit one at switch-off, none between.
            for (unsigned sensor : { pair, pair + 4 }) {
                uint8_t channel = uint8_t(EPUCK_ADC_PROXIMITY_0 + sensor);
                int at_on = 0, at_off = 0, between = 0;
                for (const Conversion &c : world.conversions) {
                    if (c.channel != channel)
                        continue;
                    at_on += c.cycle == on;
                    at_off += c.cycle == off;
                    between += c.cycle > on && c.cycle < off;
                }
                EXPECT_EQ(at_on, 1) << "sensor " << sensor;
                EXPECT_EQ(at_off, 1) << "sensor " << sensor;
                EXPECT_EQ(between, 0) << "sensor " << sensor;
            }
            // The next pair's turn comes a quarter of a full set later.
            if (i + 2 < pulses.size()) {
                EXPECT_NEAR(
                  double(pulses[i + 2].cycle - on) / FCY, 4 * 65 / scan_rate, 2 / scan_rate);
            }
        }
    }
    // Only one emitter at a time.
    int lit = 0;
    for (const PinChange &change : world.changes) {
        if (change.pin < EPUCK_PIN_IR_PULSE_0_4 || change.pin > EPUCK_PIN_IR_PULSE_3_7)
            continue;
        lit += change.high ? 1 : -1;
        EXPECT_LE(lit, 1);
        EXPECT_GE(lit, 0);
    }
}

TEST_F(Analog, FullSetsComeAboutSixtyThreeTimesASecond)
{
    start();
    std::array<int16_t, 8> prox{}, ambient{};
    int sets = take_sets_during(2.0, prox, ambient);
    EXPECT_NEAR(sets / 2.0, scan_rate / (4 * 65), 1.0);
}

// Reflected = ambient − lit; the boot calibration takes the average of the
// first 100 sets off, and the result is floored at 0 (§3.2).
TEST_F(Analog, ProximityIsReflectionLessTheBootOffsetFlooredAtZero)
{
    const std::array<uint16_t, 8> at_boot = { 100, 0, 50, 200, 10, 0, 300, 20 };
    const std::array<uint16_t, 8> later = { 400, 800, 20, 200, 1500, 0, 100, 21 };
    const std::array<uint16_t, 8> light = { 3900, 3000, 2500, 3100, 3800, 2000, 3500, 3333 };
    world.reflection = at_boot;
    world.ambient = light;
    start();
    std::array<int16_t, 8> prox{}, ambient{};
    // 100 sets at about 63 Hz: 1.6 s; a little more.
    take_sets_during(1.7, prox, ambient);
    ASSERT_TRUE(epuck_proximity_calibrated(&proximity));
    // Still at the boot situation: zero everywhere.
    for (int i = 0; i < 8; i++)
        EXPECT_EQ(prox[i], 0) << i;
    world.reflection = later;
    ASSERT_GT(take_sets_during(0.05, prox, ambient), 1);
    for (int i = 0; i < 8; i++) {
        EXPECT_EQ(prox[i], std::max(0, int(later[i]) - int(at_boot[i]))) << i;
        EXPECT_EQ(ambient[i], light[i]) << i;
    }
    EXPECT_FALSE(epuck_proximity_take(&proximity, prox.data(), ambient.data()))
      << "a set reported twice";
}

TEST_F(Analog, BeforeCalibrationSetsAreReportedWithoutOffset)
{
    world.reflection.fill(250);
    start();
    std::array<int16_t, 8> prox{}, ambient{};
    ASSERT_GT(take_sets_during(0.1, prox, ambient), 3);
    EXPECT_FALSE(epuck_proximity_calibrated(&proximity));
    for (int i = 0; i < 8; i++)
        EXPECT_EQ(prox[i], 250) << i;
}

// Offsets: X and Y their boot average, Z its boot average less one g
// (768 counts, §3.3); about 252 samples a second (one per scan cycle).
TEST_F(Analog, AccelerometerTakesItsBootOffsets)
{
    world.channel[EPUCK_ADC_ACCELEROMETER_X] = 2100;
    world.channel[EPUCK_ADC_ACCELEROMETER_Y] = 1990;
    world.channel[EPUCK_ADC_ACCELEROMETER_Z] = 2010 + 768;
    start();
    run_seconds(0.5); // 50 samples take 0.2 s
    ASSERT_TRUE(epuck_accelerometer_calibrated(&accelerometer));
    std::array<int16_t, 3> acc{};
    epuck_accelerometer_read(&accelerometer, acc.data());
    EXPECT_EQ(acc[0], 0);
    EXPECT_EQ(acc[1], 0);
    EXPECT_EQ(acc[2], 768);
    // Tilted: half a g to the right.
    world.channel[EPUCK_ADC_ACCELEROMETER_X] = 2100 + 384;
    world.channel[EPUCK_ADC_ACCELEROMETER_Z] = 2010 + 665;
    run_seconds(0.01);
    epuck_accelerometer_read(&accelerometer, acc.data());
    EXPECT_EQ(acc[0], 384);
    EXPECT_EQ(acc[2], 665);
    int samples = 0;
    for (const Conversion &c : world.conversions)
        samples += c.channel == EPUCK_ADC_ACCELEROMETER_X;
    EXPECT_NEAR(samples / 0.51, scan_rate / 65, 3.0);
}

// A square wave of amplitude A has a volume (max − min) of 2A; silence 0.
TEST_F(Analog, MicrophoneVolumeIsMaxMinusMin)
{
    const std::array<int, 3> amplitude = { 300, 0, 1000 };
    world.signal = [&](uint8_t channel, uint64_t cycle) -> uint16_t {
        if (channel < EPUCK_ADC_MICROPHONE_0 || channel > EPUCK_ADC_MICROPHONE_0 + 2)
            return 2048;
        double t = double(cycle) / FCY;
        bool high = std::fmod(t * 1000.0, 1.0) < 0.5; // 1 kHz
        int a = amplitude[channel - EPUCK_ADC_MICROPHONE_0];
        return uint16_t(2048 + (high ? a : -a));
    };
    start();
    run_seconds(0.05);
    std::array<int16_t, 3> volume{};
    epuck_microphones_read(&microphones, volume.data());
    for (int i = 0; i < 3; i++)
        EXPECT_EQ(volume[i], 2 * amplitude[i]) << i;
}

// A recording is 32 readings of each microphone one scan (1/16384 s) apart,
// less their mean, about 15 times a second (1024 of the 62 in 65 scans that
// read the microphones). The world shows each microphone a ramp that climbs
// by k + 1 counts a scan, so that consecutive readings differ by exactly
// k + 1 and a skipped scan would show as a step of 2(k + 1).
TEST_F(Analog, RecordingsAreConsecutiveScansLessTheirMean)
{
    world.signal = [&](uint8_t channel, uint64_t cycle) -> uint16_t {
        if (channel < EPUCK_ADC_MICROPHONE_0 || channel > EPUCK_ADC_MICROPHONE_0 + 2)
            return 2048;
        uint64_t scan = uint64_t(std::llround(double(cycle) / FCY * scan_rate));
        unsigned slope = unsigned(channel - EPUCK_ADC_MICROPHONE_0) + 1;
        return uint16_t(1000 + slope * (scan % 500));
    };
    start();
    std::array<std::array<int16_t, EPUCK_MICROPHONE_RECORD_SAMPLES>, 3> recorded{};
    int16_t *const recordings[3] = { recorded[0].data(), recorded[1].data(), recorded[2].data() };
    int taken = 0;
    const double seconds = 2;
    for (double t = 0; t < seconds; t += 1e-3) {
        run_seconds(1e-3);
        if (!epuck_microphones_take_recording(&microphones, recordings))
            continue;
        taken++;
        for (int k = 0; k < 3; k++) {
            int sum = 0;
            for (unsigned n = 0; n < EPUCK_MICROPHONE_RECORD_SAMPLES; n++)
                sum += recorded[k][n];
            // The ramp's mean is a half-integer for an odd slope: rounded.
            EXPECT_LE(std::abs(sum), int(EPUCK_MICROPHONE_RECORD_SAMPLES) / 2) << k;
            for (unsigned n = 1; n < EPUCK_MICROPHONE_RECORD_SAMPLES; n++) {
                int step = recorded[k][n] - recorded[k][n - 1];
                // The ramp wraps every 500 scans.
                if (step > -400) {
                    ASSERT_EQ(step, k + 1) << "microphone " << k << ", reading " << n;
                }
            }
        }
    }
    double expected_rate = scan_rate * 62 / 65 / EPUCK_MICROPHONE_RECORD_INTERVAL;
    EXPECT_NEAR(taken / seconds, expected_rate, 1.0);
    EXPECT_FALSE(epuck_microphones_take_recording(&microphones, recordings))
      << "a recording taken twice";
}

} // namespace
} // namespace drivers_test

namespace drivers_test
{
namespace
{

// Whether two microphone drivers hold the same state.
void expect_same_microphones(const epuck_microphones &a, const epuck_microphones &b)
{
    for (unsigned i = 0; i < EPUCK_MICROPHONE_COUNT; i++) {
        EXPECT_EQ(a.window_min[i], b.window_min[i]) << i;
        EXPECT_EQ(a.window_max[i], b.window_max[i]) << i;
        EXPECT_EQ(a.volume[i], b.volume[i]) << i;
        for (unsigned n = 0; n < EPUCK_MICROPHONE_RECORD_SAMPLES; n++)
            ASSERT_EQ(a.recording[i][n], b.recording[i][n]) << i << ", " << n;
    }
    EXPECT_EQ(a.window_samples, b.window_samples);
    EXPECT_EQ(a.recorded, b.recorded);
    EXPECT_EQ(a.until_next, b.until_next);
    EXPECT_EQ(a.recording_now, b.recording_now);
    EXPECT_EQ(a.recording_full, b.recording_full);
}

// A run of n scans of the same values does what n scans one at a time do,
// across window ends, recordings started, filled, broken by another
// channel's scan, and waiting to be taken.
TEST(MicrophoneRuns, ARunIsThatManyScansOfTheSameValues)
{
    auto board = std::make_unique<hal_board>();
    host_board_init(board.get(), nullptr, nullptr);
    epuck_microphones by_run{}, one_by_one{};
    epuck_microphones_init(&by_run, board.get());
    epuck_microphones_init(&one_by_one, board.get());
    std::array<std::array<int16_t, EPUCK_MICROPHONE_RECORD_SAMPLES>, 3> a{}, b{};
    int16_t *const into_a[3] = { a[0].data(), a[1].data(), a[2].data() };
    int16_t *const into_b[3] = { b[0].data(), b[1].data(), b[2].data() };
    uint32_t random = 12345;
    auto next = [&random](uint32_t below) {
        random = random * 1103515245u + 12345u;
        return (random >> 8) % below;
    };
    int runs = 0;
    for (int action = 0; action < 20000; action++) {
        uint16_t values[3] = { uint16_t(next(4096)), uint16_t(next(4096)), uint16_t(next(4096)) };
        bool follows = next(8) != 0;
        switch (next(4)) {
        case 0:
            epuck_microphones_sampled(&by_run, values, follows);
            epuck_microphones_sampled(&one_by_one, values, follows);
            break;
        case 1: {
            EXPECT_EQ(epuck_microphones_take_recording(&by_run, into_a),
                      epuck_microphones_take_recording(&one_by_one, into_b));
            EXPECT_EQ(a, b);
            break;
        }
        default: {
            uint16_t scans = uint16_t(1 + next(next(2) ? 40 : 1500));
            epuck_microphones_sampled_run(&by_run, values, follows, scans);
            for (uint16_t n = 0; n < scans; n++)
                epuck_microphones_sampled(&one_by_one, values, n == 0 ? follows : true);
            runs++;
            break;
        }
        }
        expect_same_microphones(by_run, one_by_one);
        if (::testing::Test::HasFailure())
            FAIL() << "after action " << action;
    }
    EXPECT_GT(runs, 5000);
}

// The analog drivers on a board that hands the silent microphones' scans
// over in runs (host_world.h) end every millisecond as on a board that hands
// over one scan at a time: volumes, recordings, proximity and accelerometer
// sets, the sequencer's place in its cycle; the microphones' levels change
// now and then between the board's advances.
TEST(AnalogRuns, RunsOfSteadyScansLeaveTheDriversAsSingleScansDo)
{
    struct Rig {
        std::unique_ptr<hal_board> board = std::make_unique<hal_board>();
        ModelledWorld world;
        epuck_proximity proximity{};
        epuck_accelerometer accelerometer{};
        epuck_microphones microphones{};
        epuck_analog analog{};

        explicit Rig(bool runs)
        {
            host_board_init(board.get(), nullptr, nullptr);
            world.ambient.fill(3000);
            world.reflection.fill(700);
            world.channel.fill(2048);
            world.steady_microphones = runs;
            world.attach(board.get());
            epuck_proximity_init(&proximity, board.get());
            epuck_accelerometer_init(&accelerometer, board.get());
            epuck_microphones_init(&microphones, board.get());
            EXPECT_TRUE(
              epuck_analog_start(&analog, board.get(), &proximity, &accelerometer, &microphones));
        }
        size_t microphone_conversions() const
        {
            return size_t(std::count_if(
              world.conversions.begin(), world.conversions.end(), [](const Conversion &c) {
                  return c.channel == EPUCK_ADC_MICROPHONE_0;
              }));
        }
    };
    Rig by_runs(true), one_by_one(false);
    std::array<std::array<int16_t, EPUCK_MICROPHONE_RECORD_SAMPLES>, 3> a{}, b{};
    int16_t *const into_a[3] = { a[0].data(), a[1].data(), a[2].data() };
    int16_t *const into_b[3] = { b[0].data(), b[1].data(), b[2].data() };
    int recordings = 0, sets = 0;
    bool heard = false;
    for (int ms = 0; ms < 2000; ms++) {
        if (ms % 70 == 0)
            for (unsigned i = 0; i < 3; i++)
                by_runs.world.channel[EPUCK_ADC_MICROPHONE_0 + i] =
                  one_by_one.world.channel[EPUCK_ADC_MICROPHONE_0 + i] =
                    uint16_t(2048 + (ms * 7 + int(i) * 300) % 900);
        // Advances of uneven lengths, some shorter than a scan.
        uint64_t cycles = uint64_t(FCY / 1000) * (1 + ms % 3) / 2 + uint64_t(ms % 5);
        host_board_advance(by_runs.board.get(), cycles);
        host_board_advance(one_by_one.board.get(), cycles);
        if (ms % 40 == 0) {
            bool taken = epuck_microphones_take_recording(&by_runs.microphones, into_a);
            ASSERT_EQ(taken, epuck_microphones_take_recording(&one_by_one.microphones, into_b));
            EXPECT_EQ(a, b);
            recordings += taken;
        }
        std::array<int16_t, 8> prox_a{}, ambient_a{}, prox_b{}, ambient_b{};
        bool set = epuck_proximity_take(&by_runs.proximity, prox_a.data(), ambient_a.data());
        ASSERT_EQ(set,
                  epuck_proximity_take(&one_by_one.proximity, prox_b.data(), ambient_b.data()));
        EXPECT_EQ(prox_a, prox_b);
        EXPECT_EQ(ambient_a, ambient_b);
        sets += set;
        expect_same_microphones(by_runs.microphones, one_by_one.microphones);
        std::array<int16_t, 3> volume{};
        epuck_microphones_read(&by_runs.microphones, volume.data());
        heard |= volume[0] + volume[1] + volume[2] > 0;
        ASSERT_EQ(by_runs.analog.count, one_by_one.analog.count) << ms;
        ASSERT_EQ(by_runs.analog.scanning, one_by_one.analog.scanning) << ms;
        ASSERT_EQ(by_runs.analog.previous, one_by_one.analog.previous) << ms;
        ASSERT_EQ(host_board_cycles(by_runs.board.get()),
                  host_board_cycles(one_by_one.board.get()));
    }
    EXPECT_EQ(by_runs.world.changes.size(), one_by_one.world.changes.size());
    EXPECT_GT(recordings, 10);
    EXPECT_GT(sets, 50);
    EXPECT_TRUE(heard) << "no window saw the levels change";
    // The runs did save conversions: most microphone scans came in runs.
    EXPECT_LT(by_runs.microphone_conversions() * 3, one_by_one.microphone_conversions());
}

} // namespace
} // namespace drivers_test
