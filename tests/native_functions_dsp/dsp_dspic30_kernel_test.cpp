// hal/dspic30/dspic30_dsp_kernel.c, the dsPIC DSP-engine version of the
// inner loop of dsp.fir/corr/conv, run on the host against a model of the
// XC16 DSP builtins (dspic30_dsp_engine_model.h; module.mk renames its
// function nat_dsp_scaled_dot_product_dspic30). Both it and the portable
// version (nat_dsp_kernel.c) must equal the exact sum, computed here in
// double precision (exact: |sum| < 2^53), divided by 2^shift, rounded half
// up and clamped to int16 — on random inputs, at the extremes, at rounding
// ties and at both sides of the saturation thresholds. What this cannot
// check is that the model matches the chip (hal/dspic30/README-dsp.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

extern "C" {
uint16_t dspic30_model_corcon = 0;
int16_t nat_dsp_scaled_dot_product(const int16_t *a,
                                   const int16_t *b,
                                   int16_t b_step,
                                   uint16_t count,
                                   uint16_t shift);
int16_t nat_dsp_scaled_dot_product_dspic30(const int16_t *a,
                                           const int16_t *b,
                                           int16_t b_step,
                                           uint16_t count,
                                           uint16_t shift);
}

namespace
{

using Words = std::vector<int16_t>;

constexpr uint16_t max_shift = 31;
constexpr uint16_t accumulator_exact_count = 511; // the dsPIC version's limit
constexpr uint16_t corcon_psv = 1u << 2;          // must survive the call
constexpr uint16_t corcon_interrupt_level3 = 1u << 3;

// sum a[i] * b[i * step] / 2^shift, rounded half up, clamped: in doubles.
// `b_start` is the index in b of the first term.
int16_t expected(const Words &a,
                 const Words &b,
                 size_t b_start,
                 int step,
                 uint16_t count,
                 uint16_t shift)
{
    double sum = 0;
    for (size_t i = 0; i < count; ++i)
        sum += double(a[i]) * double(b[b_start + step * std::ptrdiff_t(i)]);
    double rounded = std::floor(std::ldexp(sum, -shift) + 0.5);
    return int16_t(std::clamp(rounded, -32768.0, 32767.0));
}

// Checks both versions against the expectation, and that CORCON is restored.
void check(const Words &a, const Words &b, size_t b_start, int step, uint16_t count, uint16_t shift)
{
    const int16_t want = expected(a, b, b_start, step, count, shift);
    const int16_t *b_first = b.data() + b_start;
    SCOPED_TRACE(testing::Message() << "count " << count << " shift " << shift << " step " << step);
    EXPECT_EQ(nat_dsp_scaled_dot_product(a.data(), b_first, int16_t(step), count, shift), want);
    const uint16_t corcon_before = corcon_psv | corcon_interrupt_level3;
    dspic30_model_corcon = corcon_before;
    EXPECT_EQ(nat_dsp_scaled_dot_product_dspic30(a.data(), b_first, int16_t(step), count, shift),
              want);
    EXPECT_EQ(dspic30_model_corcon, corcon_before);
}

// Writes `sum` (|sum| < 2^38) as a[0] * b[0] + a[1] * b[1] + ...: sum = q *
// 32768 + r, 0 <= r < 32768, q in chunks of at most 32767 times -32768 * -1.
void split_into_products(int64_t sum, Words &a, Words &b)
{
    constexpr int64_t word_scale = 32768;
    int64_t remainder = ((sum % word_scale) + word_scale) % word_scale;
    int64_t quotient = (sum - remainder) / word_scale;
    while (quotient != 0) {
        int64_t chunk = std::clamp<int64_t>(quotient, -32767, 32767);
        a.push_back(int16_t(-chunk));
        b.push_back(INT16_MIN);
        quotient -= chunk;
    }
    a.push_back(int16_t(remainder));
    b.push_back(1);
}

// Both directions of b over the same words: forwards from b[0], backwards
// from b[count - 1].
void check_both_directions(const Words &a, const Words &b, uint16_t count, uint16_t shift)
{
    check(a, b, 0, 1, count, shift);
    if (count > 0)
        check(a, b, count - 1, -1, count, shift);
}

TEST(DspDspic30Kernel, RandomInputsEveryShift)
{
    std::mt19937 random(20261122);
    std::uniform_int_distribution<int> word(INT16_MIN, INT16_MAX);
    std::uniform_int_distribution<int> short_count(0, 40);
    for (uint16_t shift = 0; shift <= max_shift; ++shift) {
        for (int round = 0; round < 20; ++round) {
            // Mostly short sums, some up to the accumulator's limit and past it.
            uint16_t count =
              round < 16 ? uint16_t(short_count(random)) : uint16_t(400 + 100 * (round - 16));
            Words a(count), b(count);
            for (auto &value : a)
                value = int16_t(word(random));
            for (auto &value : b)
                value = int16_t(word(random));
            check_both_directions(a, b, count, shift);
        }
    }
}

// The largest sums in magnitude: every product (-32768)^2 = 2^30, or
// -32768 * 32767, up to the accumulator's limit (511 terms, the dsPIC
// version's engine) and past it (its portable fallback).
TEST(DspDspic30Kernel, ExtremeSums)
{
    for (uint16_t count : { 1, 2, 255, 256, 510, 511, 512, 513, 1000 }) {
        Words minimum(count, INT16_MIN), maximum(count, INT16_MAX);
        for (uint16_t shift = 0; shift <= max_shift; ++shift) {
            check_both_directions(minimum, minimum, count, shift);
            check_both_directions(minimum, maximum, count, shift);
            check_both_directions(maximum, minimum, count, shift);
            check_both_directions(maximum, maximum, count, shift);
        }
    }
}

// Sums of exactly k + 1/2 and around it after the shift, positive and
// negative: half up means -2.5 -> -2 and 2.5 -> 3.
TEST(DspDspic30Kernel, RoundingTies)
{
    for (uint16_t shift = 1; shift <= max_shift; ++shift) {
        for (int64_t quotient : { -3, -2, -1, 0, 1, 2, 32766, -32769 }) {
            for (int64_t offset : { -1, 0, 1 }) {
                // sum = (quotient + 1/2) * 2^shift + offset, within the
                // 40-bit accumulator's reach.
                int64_t sum =
                  quotient * (int64_t(1) << shift) + (int64_t(1) << (shift - 1)) + offset;
                if (std::abs(sum) >= int64_t(1) << 38)
                    continue;
                Words a, b;
                split_into_products(sum, a, b);
                ASSERT_LE(a.size(), accumulator_exact_count);
                check_both_directions(a, b, uint16_t(a.size()), shift);
            }
        }
    }
}

// Right at the int16 limits after rounding: 32767 and 32768, -32768 and
// -32769, for shifts 0 and 15 (dsp.fir's).
TEST(DspDspic30Kernel, SaturationThresholds)
{
    for (uint16_t shift : { 0, 15 }) {
        for (int64_t result : { 32766, 32767, 32768, 32769, -32767, -32768, -32769, -32770 }) {
            for (int64_t offset : { -1, 0, 1 }) {
                int64_t sum = result * (int64_t(1) << shift) + offset;
                Words a, b;
                split_into_products(sum, a, b);
                check_both_directions(a, b, uint16_t(a.size()), shift);
            }
        }
    }
}

TEST(DspDspic30Kernel, EmptySumIsZero)
{
    Words none;
    for (uint16_t shift = 0; shift <= max_shift; ++shift)
        check(none, none, 0, 1, 0, shift);
}

} // namespace
