// dsp.fir and dsp.iir against filters computed in double precision.
//
// dsp.fir sums exactly, so its error bound is the final rounding: it must
// equal the double-precision sum (exact for these integers) / 32768,
// rounded half up and clamped, bit for bit.
// dsp.iir rounds each output, and that error (at most 0.5) goes round the
// feedback loop: with g the impulse response of 1 / (1 + a1 z^-1 + a2 z^-2),
// the output stays within 0.5 * sum |g[n]| of the unrounded filter.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dsp_node.hpp"

namespace
{

constexpr uint16_t dest_address = 0;
constexpr uint16_t src_address = 300;
constexpr uint16_t coefficients_address = 600;
constexpr uint16_t state_address = 700;
constexpr uint16_t variables_size = 800;
constexpr double q15_one = 32768.0;
constexpr double q14_one = 16384.0;

// The FIR of src with Q15 taps, history zero, in double precision.
Words expected_fir(const Words &src, const Words &taps)
{
    Words result(src.size());
    for (size_t n = 0; n < src.size(); ++n) {
        double sum = 0;
        for (size_t k = 0; k < taps.size() && k <= n; ++k)
            sum += double(taps[k]) * src[n - k];
        result[n] = clamp_to_int16(round_half_up(sum, 15));
    }
    return result;
}

Words run_fir(DspNode &node, const Words &src, const Words &taps, uint16_t dest = dest_address)
{
    node.put(src_address, src);
    node.put(coefficients_address, taps);
    node.call(dsp_native("dsp.fir"),
              { static_cast<int16_t>(dest),
                src_address,
                coefficients_address,
                static_cast<int16_t>(src.size()),
                static_cast<int16_t>(taps.size()) });
    return node.get(dest, static_cast<uint16_t>(src.size()));
}

TEST(DspFir, EqualsTheExactFilterRoundedForEveryLengthAndTapCount)
{
    std::mt19937 generator(11);
    for (uint16_t length : { 1, 2, 7, 32, 64, 200 }) {
        for (uint16_t tap_count : { 1, 2, 3, 16, 32, 33, 90 }) {
            DspNode node(variables_size);
            const auto src = random_words(generator, length);
            const auto taps = random_words(generator, tap_count, -12000, 12000);
            EXPECT_EQ(run_fir(node, src, taps), expected_fir(src, taps))
              << length << " samples, " << tap_count << " taps";
            EXPECT_TRUE(node.errors.empty());
        }
    }
}

TEST(DspFir, MovingAverageOfAConstantSettlesOnTheConstant)
{
    // 8 taps of 4096 (1/8 in Q15): after 8 samples the output is the input.
    DspNode node(variables_size);
    const Words src(20, 1000);
    const auto output = run_fir(node, src, Words(8, 4096));
    for (size_t n = 0; n < src.size(); ++n)
        EXPECT_EQ(output[n], n < 8 ? 125 * (n + 1) : 1000) << n;
}

TEST(DspFir, SaturatesAtBothExtremes)
{
    DspNode node(variables_size);
    const Words taps(32, INT16_MAX);
    const auto high = run_fir(node, Words(40, INT16_MAX), taps);
    const auto low = run_fir(node, Words(40, INT16_MIN), taps);
    for (size_t n = 1; n < 40; ++n) {
        EXPECT_EQ(high[n], INT16_MAX) << n;
        EXPECT_EQ(low[n], INT16_MIN) << n;
    }
    // One tap below 1.0: the first output is not saturated.
    EXPECT_EQ(high[0], clamp_to_int16(round_half_up(32767.0 * 32767.0, 15)));
    EXPECT_EQ(low[0], clamp_to_int16(round_half_up(-32768.0 * 32767.0, 15)));
}

TEST(DspFir, FiltersInPlace)
{
    std::mt19937 generator(12);
    DspNode node(variables_size);
    const auto src = random_words(generator, 64);
    const auto taps = random_words(generator, 9, -8000, 8000);
    EXPECT_EQ(run_fir(node, src, taps, src_address), expected_fir(src, taps));
}

// The biquad as specified, unrounded, in double precision.
struct DoubleBiquad {
    double b0, b1, b2, a1, a2;
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    double step(double x)
    {
        const double y = b0 * x + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
        x2 = x1, x1 = x, y2 = y1, y1 = y;
        return y;
    }
};

// A second-order Butterworth low-pass (bilinear transform), cutoff as a
// fraction of the sampling rate, quantised to Q14.
Words butterworth_q14(double cutoff)
{
    const double k = std::tan(std::numbers::pi * cutoff);
    const double norm = 1 / (1 + std::sqrt(2.0) * k + k * k);
    const double b0 = k * k * norm;
    const double a1 = 2 * (k * k - 1) * norm;
    const double a2 = (1 - std::sqrt(2.0) * k + k * k) * norm;
    auto q14 = [](double value) { return static_cast<int16_t>(std::lround(value * q14_one)); };
    return { q14(b0), q14(2 * b0), q14(b0), q14(a1), q14(a2) };
}

// 0.5 * sum |g[n]|, g the impulse response of the feedback part.
double iir_tolerance(const Words &coefficients)
{
    DoubleBiquad feedback{ 1, 0, 0, coefficients[3] / q14_one, coefficients[4] / q14_one };
    double sum = 0;
    for (int n = 0; n < 10000; ++n)
        sum += std::abs(feedback.step(n == 0 ? 1 : 0));
    return 0.5 * sum;
}

TEST(DspIir, ButterworthLowPassFollowsTheDoubleFilterAcrossCalls)
{
    std::mt19937 generator(13);
    for (double cutoff : { 0.02, 0.1, 0.3 }) {
        const auto coefficients = butterworth_q14(cutoff);
        const double tolerance = iir_tolerance(coefficients);
        DoubleBiquad reference{ coefficients[0] / q14_one,
                                coefficients[1] / q14_one,
                                coefficients[2] / q14_one,
                                coefficients[3] / q14_one,
                                coefficients[4] / q14_one };
        DspNode node(variables_size);
        node.put(coefficients_address, coefficients);
        node.put(state_address, { 0, 0, 0, 0 });
        // Several calls on successive blocks: the state carries the history.
        for (int block = 0; block < 4; ++block) {
            const auto src = random_words(generator, 50, -16000, 16000);
            node.put(src_address, src);
            node.call(dsp_native("dsp.iir"),
                      { dest_address,
                        src_address,
                        coefficients_address,
                        state_address,
                        static_cast<int16_t>(src.size()) });
            ASSERT_TRUE(node.errors.empty());
            const auto output = node.get(dest_address, 50);
            for (size_t n = 0; n < src.size(); ++n)
                EXPECT_NEAR(output[n], reference.step(src[n]), tolerance)
                  << "cutoff " << cutoff << ", block " << block << ", sample " << n;
            // The state holds the last inputs and outputs.
            EXPECT_EQ(node.get(state_address, 4),
                      (Words{ src[49], src[48], output[49], output[48] }));
        }
    }
}

TEST(DspIir, SaturatesAtBothExtremesAndFiltersInPlace)
{
    DspNode node(variables_size);
    // y = 1.99994 x: clips for |x| > 16384.
    const Words coefficients = { INT16_MAX, 0, 0, 0, 0 };
    node.put(coefficients_address, coefficients);
    const Words src = { 30000, -30000, 16000, -16000, INT16_MAX, INT16_MIN, 0 };
    node.put(src_address, src);
    node.put(state_address, { 0, 0, 0, 0 });
    node.call(dsp_native("dsp.iir"),
              { src_address,
                src_address,
                coefficients_address,
                state_address,
                static_cast<int16_t>(src.size()) });
    Words expected;
    for (auto x : src)
        expected.push_back(clamp_to_int16(round_half_up(double(x) * INT16_MAX, 14)));
    EXPECT_EQ(node.get(src_address, static_cast<uint16_t>(src.size())), expected);
    EXPECT_EQ(expected[0], INT16_MAX);
    EXPECT_EQ(expected[1], INT16_MIN);

    // Extreme coefficients and state with full-scale input: saturates, no
    // overflow inside (the sanitizer build would stop on one).
    const Words wild = { INT16_MIN, INT16_MIN, INT16_MIN, INT16_MAX, INT16_MAX };
    node.put(coefficients_address, wild);
    node.put(state_address, { INT16_MAX, INT16_MAX, INT16_MIN, INT16_MIN });
    node.put(src_address, { INT16_MAX });
    node.call(dsp_native("dsp.iir"),
              { dest_address, src_address, coefficients_address, state_address, 1 });
    const double sum = -32768.0 * 32767 * 3 - 32767.0 * -32768 * 2;
    EXPECT_EQ(node.get(dest_address, 1)[0], clamp_to_int16(round_half_up(sum, 14)));
}

} // namespace
