// The arena's sound sources heard through the real microphone driver and
// firmware (the recordings in mic.samples0..2, the volumes in mic): the
// delays between the microphones and their amplitudes against the ones
// worked out here from the geometry (distances, 343 m/s, 1 / distance),
// the sources' schedules, and the sound-direction example turning robots
// towards a loudspeaker.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "arena_test_support.hpp"

using namespace aseba::arena;
using arena_test::compile;
using arena_test::variables;

namespace
{

constexpr double pi = 3.14159265358979323846;
constexpr double sound_speed = 34300; // cm/s
// The microphones as docs/arena-format.md places them: forward and left of
// the robot's centre (cm), right, left and back.
constexpr double microphone_forward[3] = { 0.835, 0.835, -2.305 };
constexpr double microphone_left[3] = { -3.03, 3.03, 0 };

struct Tone {
    double amplitude;
    double phase; // radians, of sin(ω t + phase) at the first reading
};

// The least-squares fit of a·sin(ω t) + b·cos(ω t) + c to readings taken
// `rate` times a second.
Tone fit_tone(const int16_t *samples, size_t count, double frequency, double rate)
{
    // Normal equations of the three basis functions.
    double m[3][4] = {};
    for (size_t n = 0; n < count; n++) {
        double t = double(n) / rate;
        double basis[3] = { std::sin(2 * pi * frequency * t), std::cos(2 * pi * frequency * t), 1 };
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++)
                m[i][j] += basis[i] * basis[j];
            m[i][3] += basis[i] * samples[n];
        }
    }
    for (int i = 0; i < 3; i++) // Gauss-Jordan
        for (int k = 0; k < 3; k++) {
            if (k == i)
                continue;
            double factor = m[k][i] / m[i][i];
            for (int j = 0; j < 4; j++)
                m[k][j] -= factor * m[i][j];
        }
    double a = m[0][3] / m[0][0], b = m[1][3] / m[1][1];
    return { std::hypot(a, b), std::atan2(b, a) };
}

struct Geometry {
    double robot_x, robot_y, heading_degrees;
    double source_x, source_y;
};

class SoundGeometry : public testing::TestWithParam<Geometry>
{
};

} // namespace

// Sound from (source_x, source_y) reaches microphone k after d_k / 343 m/s
// with an amplitude of level × 10 cm / d_k: the recordings' phases differ by
// the differences of those delays, and their amplitudes are in those ratios.
TEST_P(SoundGeometry, DelaysAndAmplitudesFollowTheDistances)
{
    const Geometry g = GetParam();
    constexpr double frequency = 1000, level = 400;
    Arena arena;
    arena.robots = { { 1, g.robot_x, g.robot_y, g.heading_degrees } };
    SoundSource source;
    source.x = g.source_x;
    source.y = g.source_y;
    source.frequency = frequency;
    source.level = level;
    arena.sounds = { source };
    ArenaSimulation simulation(arena, 1, {});
    simulation.run_for(0.2);
    const epuck_named_variables &named = simulation.firmware(0).variables.named;
    const int16_t *recordings[3] = { named.mic_samples0, named.mic_samples1, named.mic_samples2 };

    double heading = g.heading_degrees * pi / 180;
    double distance[3];
    Tone tone[3];
    for (int k = 0; k < 3; k++) {
        double x = g.robot_x + microphone_forward[k] * std::cos(heading) -
                   microphone_left[k] * std::sin(heading);
        double y = g.robot_y + microphone_forward[k] * std::sin(heading) +
                   microphone_left[k] * std::cos(heading);
        distance[k] = std::hypot(x - g.source_x, y - g.source_y);
        tone[k] = fit_tone(recordings[k], 32, frequency, 16384);
        // ADC rounding is the only error: well under 1 %.
        EXPECT_NEAR(tone[k].amplitude, level * 10 / distance[k], 0.01 * level * 10 / distance[k])
          << "microphone " << k;
    }
    for (auto [a, b] : { std::pair{ 0, 1 }, std::pair{ 0, 2 }, std::pair{ 1, 2 } }) {
        // How much later b hears the tone than a, from the geometry and
        // from the recordings' phases (a later tone has a smaller phase).
        double expected = (distance[b] - distance[a]) / sound_speed;
        double measured =
          std::remainder(tone[a].phase - tone[b].phase, 2 * pi) / (2 * pi * frequency);
        std::printf("    microphone %d after %d: %+7.2f µs measured, %+7.2f µs from the geometry\n",
                    b,
                    a,
                    measured * 1e6,
                    expected * 1e6);
        EXPECT_NEAR(measured, expected, 0.5e-6) << "microphone " << b << " after " << a;
    }
}

INSTANTIATE_TEST_SUITE_P(Places,
                         SoundGeometry,
                         testing::Values(Geometry{ 50, 50, 0, 50, 20 },      // on the right
                                         Geometry{ 50, 50, 0, 80, 50 },      // ahead
                                         Geometry{ 50, 50, 90, 20, 30 },     // behind, left
                                         Geometry{ 30, 70, -135, 40, 75 })); // behind, right

TEST(Sound, SourcesSoundOnTheirScheduleAfterTheTravelTime)
{
    // A robot facing +x, 343 cm left of a source (10 ms of travel) and 34.3
    // cm right of another (1 ms); both sound from 0.5 s to 0.8 s.
    Arena arena;
    arena.width = 400;
    arena.robots = { { 1, 350, 50, 0 } };
    SoundSource far, near;
    far.x = 7;
    near.x = 350 + 34.3;
    far.y = near.y = 50;
    far.level = near.level = 400;
    far.start = near.start = 0.5;
    far.stop = near.stop = 0.8;
    ArenaSimulation near_only(
      [&] {
          Arena one = arena;
          one.sounds = { near };
          return one;
      }(),
      1,
      {});
    ArenaSimulation far_only(
      [&] {
          Arena one = arena;
          one.sounds = { far };
          return one;
      }(),
      1,
      {});
    // The volume is max - min over the last 100 readings (about 6 ms).
    auto volume = [](ArenaSimulation &simulation) {
        return simulation.firmware(0).variables.named.mic[1];
    };
    near_only.run_for(0.5);
    far_only.run_for(0.5);
    EXPECT_EQ(volume(near_only), 0) << "heard before it sounds";
    near_only.run_for(0.01);
    far_only.run_for(0.01);
    EXPECT_GT(volume(near_only), 0) << "1 ms away, sounding since 9 ms";
    EXPECT_EQ(volume(far_only), 0) << "10 ms away: only just arriving";
    near_only.run_for(0.1);
    far_only.run_for(0.1);
    // Twice the amplitude at the left microphone, 0.835 cm ahead of the
    // centre and 3.03 cm to the left.
    double near_distance = std::hypot(34.3 - 0.835, 3.03);
    double far_distance = std::hypot(343 + 0.835, 3.03);
    EXPECT_NEAR(volume(near_only), 2 * 400 * 10 / near_distance, 3);
    EXPECT_NEAR(volume(far_only), 2 * 400 * 10 / far_distance, 2);
    near_only.run_for(0.3); // to 0.91 s: a whole window after 0.801 s
    EXPECT_EQ(volume(near_only), 0) << "heard after it stopped";
}

TEST(Sound, BeepsComeAndGo)
{
    Arena arena;
    arena.robots = { { 1, 50, 50, 0 } };
    SoundSource beeper;
    beeper.x = 60;
    beeper.y = 50;
    beeper.level = 200;
    beeper.beep_on = 0.1;
    beeper.beep_off = 0.1;
    arena.sounds = { beeper };
    ArenaSimulation simulation(arena, 1, {});
    const epuck_named_variables &named = simulation.firmware(0).variables.named;
    // On in [0, 0.1), [0.2, 0.3)...: sampled in the middle of each half.
    for (int half = 0; half < 6; half++) {
        simulation.run_for(half == 0 ? 0.06 : 0.1);
        if (half % 2 == 0)
            EXPECT_GT(named.mic[0], 100) << "half " << half;
        else
            EXPECT_EQ(named.mic[0], 0) << "half " << half;
    }
}

// examples/sound.arena: four robots around a loudspeaker, facing every way,
// running examples/sound-direction.aesl, end up facing it.
TEST(Sound, SoundDirectionExampleTurnsRobotsTowardsTheSource)
{
    Arena arena = read_arena_file("examples/sound.arena");
    ASSERT_EQ(arena.sounds.size(), 1u);
    ArenaSimulation simulation(arena, 1, compile("examples/sound-direction.aesl"));
    simulation.run_for(6);
    for (size_t i = 0; i < simulation.robot_count(); i++) {
        Pose pose = simulation.world().pose(i);
        double towards = std::atan2(arena.sounds[0].y - pose.y, arena.sounds[0].x - pose.x);
        double error = std::remainder(pose.heading - towards, 2 * pi) * 180 / pi;
        std::printf("    robot %zu: %+6.1f° from the source's direction\n", i + 1, error);
        // The left-right delay is a whole number of readings: within about
        // 14° of straight ahead it reads 0 (docs/arena-format.md).
        EXPECT_LT(std::abs(error), 20) << "robot " << i + 1;
    }
}
