// The RC5 decoder against generated frames: 14 bits of 1.778 ms (two start
// bits, toggle, 5 address bits, 6 command bits, MSB first), Manchester coded
// in half bits of 889 µs, a 1 being a half bit without carrier then one
// with; the receiver's output is low while it sees the carrier (§3.9).

#include "modelled_world.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

extern "C" {
#include "robots/epuck/devices/epuck_rc5.h"
}

namespace drivers_test
{
namespace
{

constexpr double half_bit = 889e-6;

struct Frame {
    unsigned toggle, address, command;
};

// The receiver's output level at `t` seconds for a frame starting at `start`
// (the beginning of the first start bit).
bool receiver_level(const Frame &frame, double start, double t)
{
    unsigned bits =
      (1u << 13) | (1u << 12) | (frame.toggle << 11) | (frame.address << 6) | frame.command;
    double into = t - start;
    if (into < 0 || into >= 28 * half_bit)
        return true; // idle
    int half = int(into / half_bit);
    bool one = (bits >> (13 - half / 2)) & 1u;
    bool carrier = (half % 2 == 1) == one; // a 1: carrier in its second half
    return !carrier;
}

struct Rc5 : ::testing::Test {
    std::unique_ptr<hal_board> board = std::make_unique<hal_board>();
    ModelledWorld world;
    epuck_rc5 rc5{};
    std::vector<std::pair<Frame, double>> frames;

    void SetUp() override
    {
        host_board_init(board.get(), nullptr, nullptr);
        world.input_signal = [this](epuck_pin pin, uint64_t cycle) {
            if (pin != EPUCK_PIN_REMOTE)
                return pin == EPUCK_PIN_BATTERY_LOW;
            double t = double(cycle) / FCY;
            for (auto &[frame, start] : frames)
                if (!receiver_level(frame, start, t))
                    return false;
            return true;
        };
        world.attach(board.get());
        ASSERT_TRUE(epuck_rc5_init(&rc5, board.get()));
    }
    // Runs `seconds` at once, leaving the board to find the remote's edges.
    void run_unpolled(double seconds)
    {
        host_board_advance(board.get(), uint64_t(seconds * FCY));
    }
    // Runs `seconds`, telling the board about the remote line every 10 µs.
    void run_seconds(double seconds)
    {
        const uint64_t step = uint64_t(10e-6 * FCY);
        uint64_t steps = uint64_t(seconds / 10e-6);
        for (uint64_t i = 0; i < steps; i++) {
            host_board_advance(board.get(), step);
            host_board_input_changed(board.get(), EPUCK_PIN_REMOTE);
        }
    }
};

class Rc5Frames
  : public Rc5
  , public ::testing::WithParamInterface<Frame>
{
};

TEST_P(Rc5Frames, DecodesToggleAddressAndCommand)
{
    Frame sent = GetParam();
    frames.push_back({ sent, 0.005 });
    run_seconds(0.05);
    uint8_t toggle = 9, address = 99, command = 99;
    ASSERT_TRUE(epuck_rc5_take(&rc5, &toggle, &address, &command));
    EXPECT_EQ(toggle, sent.toggle);
    EXPECT_EQ(address, sent.address);
    EXPECT_EQ(command, sent.command);
    EXPECT_FALSE(epuck_rc5_take(&rc5, &toggle, &address, &command)) << "one frame, taken twice";
}

INSTANTIATE_TEST_SUITE_P(Commands,
                         Rc5Frames,
                         ::testing::Values(Frame{ 0, 0, 12 }, // standby (§3.9)
                                           Frame{ 1, 0, 13 }, // mute
                                           Frame{ 0, 5, 16 }, // volume up, VCR
                                           Frame{ 1, 31, 63 },
                                           Frame{ 0, 21, 42 },
                                           Frame{ 1, 10, 21 },
                                           Frame{ 0, 0, 0 }));

TEST_F(Rc5, DecodesFramesOneAfterAnother)
{
    // A remote repeats its frame every 114 ms while a key is held.
    frames.push_back({ { 0, 0, 32 }, 0.005 });
    frames.push_back({ { 1, 0, 33 }, 0.119 });
    uint8_t toggle, address, command;
    run_seconds(0.1);
    ASSERT_TRUE(epuck_rc5_take(&rc5, &toggle, &address, &command));
    EXPECT_EQ(command, 32);
    EXPECT_EQ(toggle, 0);
    run_seconds(0.1);
    ASSERT_TRUE(epuck_rc5_take(&rc5, &toggle, &address, &command));
    EXPECT_EQ(command, 33);
    EXPECT_EQ(toggle, 1);
}

// The host board signals the falling edge at the cycle the world announces
// it (host_world.h, next_input_change), as INT0 would on the chip: no need
// to tell it about the line in between.
TEST_F(Rc5, DecodesWithTheEdgesTheWorldAnnounces)
{
    const double start = 0.005;
    frames.push_back({ { 1, 20, 45 }, start });
    uint8_t toggle, address, command;
    // Unannounced and unpolled, the first edge goes unseen.
    run_unpolled(0.05);
    EXPECT_FALSE(epuck_rc5_take(&rc5, &toggle, &address, &command));
    // Announced: every half-bit boundary of the frames.
    frames[0].second = 0.06;
    world.next_input_change = [this](uint64_t after) {
        for (auto &[frame, begin] : frames)
            for (int half = 0; half <= 28; half++) {
                uint64_t boundary = uint64_t(std::ceil((begin + half * half_bit) * FCY));
                if (boundary > after)
                    return boundary;
            }
        return HOST_NO_INPUT_CHANGE;
    };
    run_unpolled(0.05);
    ASSERT_TRUE(epuck_rc5_take(&rc5, &toggle, &address, &command));
    EXPECT_EQ(toggle, 1);
    EXPECT_EQ(address, 20);
    EXPECT_EQ(command, 45);
}

// A short glitch is not a frame: the line is high again at the check.
TEST_F(Rc5, IgnoresAGlitch)
{
    world.input_signal = [](epuck_pin pin, uint64_t cycle) {
        double t = double(cycle) / FCY;
        if (pin == EPUCK_PIN_REMOTE)
            return !(t > 0.005 && t < 0.0055);
        return pin == EPUCK_PIN_BATTERY_LOW;
    };
    run_seconds(0.05);
    uint8_t toggle, address, command;
    EXPECT_FALSE(epuck_rc5_take(&rc5, &toggle, &address, &command));
    // And it listens again afterwards.
    world.input_signal = [this](epuck_pin pin, uint64_t cycle) {
        double t = double(cycle) / FCY;
        if (pin == EPUCK_PIN_REMOTE)
            return receiver_level({ 1, 3, 7 }, 0.06, t);
        return pin == EPUCK_PIN_BATTERY_LOW;
    };
    run_seconds(0.05);
    ASSERT_TRUE(epuck_rc5_take(&rc5, &toggle, &address, &command));
    EXPECT_EQ(address, 3);
    EXPECT_EQ(command, 7);
}

} // namespace
} // namespace drivers_test
