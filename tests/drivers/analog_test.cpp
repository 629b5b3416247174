// The analog drivers on the host board's ADC scan: proximity pulse and
// sample timing and calibration (hardware §3.2), accelerometer offsets
// (§3.3) and microphone volume (§3.4), against a modelled world.

#include "modelled_world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

extern "C" {
#include "drivers/epuck/epuck_analog.h"
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

} // namespace
} // namespace drivers_test
