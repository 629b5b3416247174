// Stepper motors: the phase lines seen by the world follow the full-step
// sequence of hardware §3.6 in the right direction for each motor, at the
// commanded number of steps per simulated second, with the step counters
// following, and every coil off when stopped.

#include "modelled_world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

extern "C" {
#include "robots/epuck/devices/epuck_motors.h"
}

namespace drivers_test
{
namespace
{

// The fact sheet's full-step table (§3.6): A, B, C, D for phase index 0..3.
constexpr std::array<std::array<bool, 4>, 4> sequence = { {
  { false, true, false, true },
  { false, true, true, false },
  { true, false, true, false },
  { true, false, false, true },
} };

struct Motors : ::testing::Test {
    std::unique_ptr<hal_board> board = std::make_unique<hal_board>();
    ModelledWorld world;
    epuck_motor left{};
    epuck_motor right{};

    void SetUp() override
    {
        host_board_init(board.get(), nullptr, nullptr);
        world.attach(board.get());
        epuck_motor_init(&left, board.get(), EPUCK_MOTOR_LEFT);
        epuck_motor_init(&right, board.get(), EPUCK_MOTOR_RIGHT);
        world.changes.clear();
    }

    void run_seconds(double seconds)
    {
        host_board_advance(board.get(), uint64_t(std::llround(seconds * FCY)));
    }

    // The states of a motor's four phase lines after each step, from the
    // world's record, with the cycle of each.
    std::vector<std::pair<std::array<bool, 4>, uint64_t>> states(epuck_pin first) const
    {
        std::vector<std::pair<std::array<bool, 4>, uint64_t>> result;
        std::array<bool, 4> state{};
        for (int i = 0; i < 4; i++)
            state[i] = false;
        bool pending = false;
        uint64_t cycle = 0;
        for (const PinChange &change : world.changes) {
            if (change.pin < first || change.pin >= first + 4)
                continue;
            if (pending && change.cycle != cycle)
                result.push_back({ state, cycle });
            state[change.pin - first] = change.high;
            cycle = change.cycle;
            pending = true;
        }
        if (pending)
            result.push_back({ state, cycle });
        return result;
    }
};

int index_in_sequence(const std::array<bool, 4> &state)
{
    for (int i = 0; i < 4; i++)
        if (sequence[i] == state)
            return i;
    return -1;
}

TEST_F(Motors, InitLeavesEveryCoilOff)
{
    for (int pin = EPUCK_PIN_MOTOR_LEFT_A; pin <= EPUCK_PIN_MOTOR_RIGHT_D; pin++)
        EXPECT_FALSE(world.output[pin]) << pin;
    EXPECT_EQ(epuck_motor_steps(&left), 0);
}

// Forward, the left motor's phase index goes down and the right's up (§3.6).
TEST_F(Motors, ForwardStepsTheSequenceInMirroredDirections)
{
    epuck_motor_set_speed(&left, 200);
    epuck_motor_set_speed(&right, 200);
    run_seconds(0.1);
    for (auto [first, expected_delta] :
         { std::pair{ EPUCK_PIN_MOTOR_LEFT_A, 3 }, std::pair{ EPUCK_PIN_MOTOR_RIGHT_A, 1 } }) {
        auto seen = states(first);
        ASSERT_GE(seen.size(), 10u);
        for (size_t i = 0; i < seen.size(); i++) {
            int index = index_in_sequence(seen[i].first);
            ASSERT_GE(index, 0) << "not a state of the full-step table, step " << i;
            if (i > 0) {
                EXPECT_EQ(index, (index_in_sequence(seen[i - 1].first) + expected_delta) % 4)
                  << "step " << i;
            }
        }
    }
    EXPECT_GT(epuck_motor_steps(&left), 0);
    EXPECT_GT(epuck_motor_steps(&right), 0);
}

TEST_F(Motors, BackwardReversesTheSequenceAndTheCounter)
{
    epuck_motor_set_speed(&left, -300);
    epuck_motor_set_speed(&right, -300);
    run_seconds(0.1);
    auto left_states = states(EPUCK_PIN_MOTOR_LEFT_A);
    auto right_states = states(EPUCK_PIN_MOTOR_RIGHT_A);
    ASSERT_GE(left_states.size(), 10u);
    ASSERT_GE(right_states.size(), 10u);
    for (size_t i = 1; i < left_states.size(); i++)
        EXPECT_EQ(index_in_sequence(left_states[i].first),
                  (index_in_sequence(left_states[i - 1].first) + 1) % 4);
    for (size_t i = 1; i < right_states.size(); i++)
        EXPECT_EQ(index_in_sequence(right_states[i].first),
                  (index_in_sequence(right_states[i - 1].first) + 3) % 4);
    EXPECT_EQ(epuck_motor_steps(&left), -int(left_states.size()));
    EXPECT_EQ(epuck_motor_steps(&right), -int(right_states.size()));
}

// In one simulated second a motor makes as many steps as its speed, each
// 1/speed seconds after the last.
class MotorRate
  : public Motors
  , public ::testing::WithParamInterface<int>
{
};

TEST_P(MotorRate, StepsPerSecondFollowTheCommandedSpeed)
{
    int speed = GetParam();
    // Long enough for a few steps at the slowest speeds.
    double seconds = std::max(1.0, 3.0 / std::abs(speed));
    epuck_motor_set_speed(&left, int16_t(speed));
    run_seconds(seconds);
    auto seen = states(EPUCK_PIN_MOTOR_LEFT_A);
    int expected = std::abs(speed);
    EXPECT_NEAR(double(seen.size()), expected * seconds, 1.0);
    EXPECT_EQ(epuck_motor_steps(&left), speed > 0 ? int(seen.size()) : -int(seen.size()));
    ASSERT_GE(seen.size(), 2u);
    double interval = double(seen[1].second - seen[0].second) / FCY;
    EXPECT_NEAR(interval, 1.0 / expected, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Speeds,
                         MotorRate,
                         ::testing::Values(1, 7, 100, 333, 999, 1000, -1000, -50));

TEST_F(Motors, SpeedIsClampedToTheApiRange)
{
    epuck_motor_set_speed(&right, 5000);
    EXPECT_EQ(epuck_motor_speed(&right), 1000);
    epuck_motor_set_speed(&right, -32768);
    EXPECT_EQ(epuck_motor_speed(&right), -1000);
    run_seconds(0.5);
    EXPECT_NEAR(double(epuck_motor_steps(&right)), -500.0, 1.0);
}

TEST_F(Motors, StoppingSwitchesEveryCoilOffAndKeepsTheCount)
{
    epuck_motor_set_speed(&left, 500);
    run_seconds(0.1);
    int16_t counted = epuck_motor_steps(&left);
    EXPECT_NEAR(double(counted), 50.0, 1.0);
    epuck_motor_set_speed(&left, 0);
    for (int pin = EPUCK_PIN_MOTOR_LEFT_A; pin <= EPUCK_PIN_MOTOR_LEFT_D; pin++)
        EXPECT_FALSE(world.output[pin]) << pin;
    size_t changes = world.changes.size();
    run_seconds(0.5);
    EXPECT_EQ(world.changes.size(), changes) << "a stopped motor still steps";
    EXPECT_EQ(epuck_motor_steps(&left), counted);
}

} // namespace
} // namespace drivers_test
