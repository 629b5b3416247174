// dsp.corr, dsp.conv and dsp.peak against direct sums in double precision.
// The natives sum exactly, so the bound is the final rounding: results must
// equal the exact sum / 2^shift, rounded half up and clamped, bit for bit.
#include <gtest/gtest.h>

#include "dsp_node.hpp"

namespace
{

constexpr uint16_t dest_address = 0;
constexpr uint16_t a_address = 300;
constexpr uint16_t b_address = 600;
constexpr uint16_t shift_address = 900;
constexpr uint16_t variables_size = 1000;

// dest[i] = sum over n of a[n + lag] b[n], lag = i - dest_size / 2.
Words expected_correlation(const Words &a, const Words &b, size_t dest_size, int shift)
{
    Words result(dest_size);
    for (size_t i = 0; i < dest_size; ++i) {
        const long lag = long(i) - long(dest_size / 2);
        double sum = 0;
        for (long n = 0; n < long(b.size()); ++n)
            if (n + lag >= 0 && n + lag < long(a.size()))
                sum += double(a[n + lag]) * b[n];
        result[i] = clamp_to_int16(round_half_up(sum, shift));
    }
    return result;
}

// dest[i] = sum over k of a[k] b[i - k].
Words expected_convolution(const Words &a, const Words &b, size_t dest_size, int shift)
{
    Words result(dest_size);
    for (size_t i = 0; i < dest_size; ++i) {
        double sum = 0;
        for (size_t k = 0; k < a.size(); ++k)
            if (i >= k && i - k < b.size())
                sum += double(a[k]) * b[i - k];
        result[i] = clamp_to_int16(round_half_up(sum, shift));
    }
    return result;
}

Words run(DspNode &node,
          const vm_native &native,
          const Words &a,
          const Words &b,
          size_t dest_size,
          int shift)
{
    node.put(a_address, a);
    node.put(b_address, b);
    node.put(shift_address, { static_cast<int16_t>(shift) });
    node.call(native,
              { dest_address,
                a_address,
                b_address,
                shift_address,
                static_cast<int16_t>(dest_size),
                static_cast<int16_t>(a.size()),
                static_cast<int16_t>(b.size()) });
    return node.get(dest_address, static_cast<uint16_t>(dest_size));
}

TEST(DspCorrAndConv, EqualTheDirectSumsForEverySizeAndShift)
{
    std::mt19937 generator(21);
    for (size_t a_size : { 1, 5, 32, 64 }) {
        for (size_t b_size : { 1, 4, 32, 70 }) {
            const size_t full = a_size + b_size - 1;
            for (size_t dest_size : { size_t(1), size_t(2), size_t(9), full, full + 3 }) {
                for (int shift : { 0, 7, 15, 20, 31 }) {
                    DspNode node(variables_size);
                    const auto a = random_words(generator, a_size);
                    const auto b = random_words(generator, b_size);
                    EXPECT_EQ(run(node, dsp_native("dsp.corr"), a, b, dest_size, shift),
                              expected_correlation(a, b, dest_size, shift))
                      << a_size << " " << b_size << " " << dest_size << " " << shift;
                    EXPECT_EQ(run(node, dsp_native("dsp.conv"), a, b, dest_size, shift),
                              expected_convolution(a, b, dest_size, shift))
                      << a_size << " " << b_size << " " << dest_size << " " << shift;
                    EXPECT_TRUE(node.errors.empty());
                }
            }
        }
    }
}

TEST(DspCorr, FindsTheDelayBetweenTwoNoisySignals)
{
    // a is b delayed by `delay` samples: the correlation peaks at lag delay.
    std::mt19937 generator(22);
    constexpr size_t length = 32;
    for (int delay = -6; delay <= 6; ++delay) {
        const auto source = random_words(generator, length + 20, -2000, 2000);
        Words a(length), b(length);
        for (size_t n = 0; n < length; ++n) {
            b[n] = source[n + 10];
            a[n] = source[n + 10 - delay];
        }
        DspNode node(variables_size);
        const size_t lags = 2 * length - 1;
        run(node, dsp_native("dsp.corr"), a, b, lags, 10);
        node.call(dsp_native("dsp.peak"), { 950, 951, dest_address, static_cast<int16_t>(lags) });
        EXPECT_EQ(node.get(950, 1)[0] - int(lags / 2), delay);
    }
}

TEST(DspCorrAndConv, SaturateAndRefuseShiftsOutside0To31)
{
    DspNode node(variables_size);
    const Words high(64, INT16_MAX), low(64, INT16_MIN);
    EXPECT_EQ(run(node, dsp_native("dsp.corr"), high, low, 3, 15), Words(3, INT16_MIN));
    EXPECT_EQ(run(node, dsp_native("dsp.conv"), low, low, 3, 0), Words(3, INT16_MAX));
    // 64 * 2^30 >> 31 = 32: exact even at the widest sums.
    EXPECT_EQ(run(node, dsp_native("dsp.corr"), low, low, 1, 31), Words(1, 32));
    ASSERT_TRUE(node.errors.empty());

    for (const vm_native *native : { &dsp_native("dsp.corr"), &dsp_native("dsp.conv") }) {
        for (int shift : { -1, 32, INT16_MIN, INT16_MAX }) {
            DspNode refusing(variables_size);
            run(refusing, *native, high, high, 3, shift);
            ASSERT_EQ(refusing.errors.size(), 1u);
            EXPECT_EQ(refusing.errors[0].kind, DspError::Kind::node_specific);
            EXPECT_TRUE(refusing.stopped());
            EXPECT_EQ(refusing.get(dest_address, 3), Words(3, 0))
              << description_of(*native).name << shift;
        }
    }
}

TEST(DspPeak, GivesTheIndexAndValueOfTheFirstMaximum)
{
    std::mt19937 generator(23);
    for (size_t size : { 1, 2, 17, 128 }) {
        DspNode node(variables_size);
        auto src = random_words(generator, size, -50, 50); // many ties
        node.put(a_address, src);
        node.call(dsp_native("dsp.peak"), { 0, 1, a_address, static_cast<int16_t>(size) });
        const auto best = std::max_element(src.begin(), src.end()); // first of the largest
        EXPECT_EQ(node.get(0, 2), (Words{ static_cast<int16_t>(best - src.begin()), *best }));
    }
    // All equal, negative extremes: index 0.
    DspNode node(variables_size);
    node.put(a_address, Words(5, INT16_MIN));
    node.call(dsp_native("dsp.peak"), { 0, 1, a_address, 5 });
    EXPECT_EQ(node.get(0, 2), (Words{ 0, INT16_MIN }));

    // The outputs inside src: the search reads src before writing.
    node.put(a_address, { 3, 9, 9, 1 });
    node.call(dsp_native("dsp.peak"), { a_address + 1, a_address, a_address, 4 });
    EXPECT_EQ(node.get(a_address, 2), (Words{ 9, 1 }));
}

} // namespace
