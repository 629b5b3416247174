// dsp.fft and dsp.mag against a DFT computed in double precision.
//
// Error bound of dsp.fft, per output, in complex magnitude (LSB): a stage's
// output (a +- W b) / 2 carries half the errors of a and b, i.e. no more
// than their largest, and adds new ones: the rounding of W b to an integer
// (at most 0.5 per part, 0.71 in magnitude), the Q15 twiddle quantisation
// (|dW| <= 2^-15 with the 32767 entry, times |b| <= 32768: 1), both halved,
// and the rounding of the halving (0.71): 1.56 per stage. The bound used,
// 1.5 * sqrt(2) = 2.12 per stage, rounds that up. (Measured over random
// inputs: worst 1.9 at N = 8, 3.4 at N = 128; RMS about 1.)
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "dsp_node.hpp"

namespace
{

using Complex = std::complex<double>;

constexpr uint16_t real_address = 0;
constexpr uint16_t imag_address = 200;
constexpr uint16_t dest_address = 400;
constexpr uint16_t variables_size = 600;
const uint16_t fft_sizes[] = { 8, 16, 32, 64, 128 };

double fft_tolerance(uint16_t size)
{
    return 1.5 * std::sqrt(2.0) * std::log2(size);
}

// X[k] / N of the integer input, in double precision.
std::vector<Complex> scaled_dft(const Words &real, const Words &imag)
{
    const size_t size = real.size();
    std::vector<Complex> result(size);
    for (size_t k = 0; k < size; ++k) {
        Complex sum = 0;
        for (size_t n = 0; n < size; ++n)
            sum += Complex(real[n], imag[n]) *
                   std::polar(1.0, -2 * std::numbers::pi * double(k * n % size) / double(size));
        result[k] = sum / double(size);
    }
    return result;
}

struct Spectrum {
    Words real;
    Words imag;
};

Spectrum run_fft(DspNode &node, const Words &real, const Words &imag)
{
    node.put(real_address, real);
    node.put(imag_address, imag);
    const auto size = static_cast<int16_t>(real.size());
    node.call(dsp_native("dsp.fft"), { real_address, imag_address, size });
    return { node.get(real_address, size), node.get(imag_address, size) };
}

// Every output within the tolerance of the double-precision DFT / N.
void expect_close_to_dft(const Words &real, const Words &imag, const Spectrum &spectrum)
{
    const auto expected = scaled_dft(real, imag);
    const double tolerance = fft_tolerance(static_cast<uint16_t>(real.size()));
    for (size_t k = 0; k < real.size(); ++k) {
        const Complex got(spectrum.real[k], spectrum.imag[k]);
        EXPECT_LE(std::abs(got - expected[k]), tolerance)
          << "N = " << real.size() << ", bin " << k << ": got " << got << ", expected "
          << expected[k];
    }
}

TEST(DspFft, PureToneOfEveryBinAndSizePeaksWithHalfItsAmplitude)
{
    constexpr double amplitude = 20000;
    for (uint16_t size : fft_sizes) {
        for (uint16_t bin = 1; bin < size / 2; ++bin) {
            DspNode node(variables_size);
            Words real(size), imag(size, 0);
            for (uint16_t n = 0; n < size; ++n)
                real[n] = static_cast<int16_t>(
                  std::lround(amplitude * std::cos(2 * std::numbers::pi * bin * n / size + 0.3)));
            const auto spectrum = run_fft(node, real, imag);
            ASSERT_TRUE(node.errors.empty());
            expect_close_to_dft(real, imag, spectrum);

            // The magnitude spectrum peaks at the tone's bin (and its mirror)
            // with amplitude / 2: the tone splits between bins k and N - k.
            node.call(dsp_native("dsp.mag"),
                      { dest_address, real_address, imag_address, static_cast<int16_t>(size) });
            const auto magnitude = node.get(dest_address, size);
            int16_t index = -1, value = -1;
            for (uint16_t k = 0; k <= size / 2; ++k)
                if (magnitude[k] > value)
                    value = magnitude[k], index = static_cast<int16_t>(k);
            EXPECT_EQ(index, bin) << "N = " << size;
            EXPECT_NEAR(value, amplitude / 2, fft_tolerance(size) + 1) << "N = " << size;
        }
    }
}

TEST(DspFft, RandomComplexInputsMatchTheDftAndKeepTheirEnergy)
{
    std::mt19937 generator(9);
    for (uint16_t size : fft_sizes) {
        for (int trial = 0; trial < 5; ++trial) {
            DspNode node(variables_size);
            // Complex magnitudes below 32768: the range where no stage saturates.
            const auto real = random_words(generator, size, -23000, 23000);
            const auto imag = random_words(generator, size, -23000, 23000);
            const auto spectrum = run_fft(node, real, imag);
            expect_close_to_dft(real, imag, spectrum);

            // Parseval: sum |X/N|^2 = sum |x|^2 / N, to the rounding errors.
            double input_energy = 0, output_energy = 0;
            for (uint16_t n = 0; n < size; ++n) {
                input_energy += double(real[n]) * real[n] + double(imag[n]) * imag[n];
                output_energy += double(spectrum.real[n]) * spectrum.real[n] +
                                 double(spectrum.imag[n]) * spectrum.imag[n];
            }
            EXPECT_NEAR(output_energy, input_energy / size, 0.02 * input_energy / size);
        }
    }
}

TEST(DspFft, FullScaleInputsSaturateInsteadOfWrapping)
{
    for (uint16_t size : fft_sizes) {
        DspNode node(variables_size);
        // A full-scale square wave: the first stage's differences are
        // (32767 + 32768) / 2 = 32767.5, which must clip to 32767.
        Words real(size), imag(size, 0);
        for (uint16_t n = 0; n < size; ++n)
            real[n] = n < size / 2 ? INT16_MAX : INT16_MIN;
        expect_close_to_dft(real, imag, run_fft(node, real, imag));

        // Constant full-scale complex input: all energy at bin 0.
        Words constant_real(size, INT16_MIN), constant_imag(size, INT16_MAX);
        expect_close_to_dft(
          constant_real, constant_imag, run_fft(node, constant_real, constant_imag));
        EXPECT_TRUE(node.errors.empty());
    }
}

TEST(DspFft, SizesThatAreNotPowersOfTwoFrom8To128AreRefused)
{
    for (int size : { 0, 1, 2, 4, 6, 7, 12, 24, 100, 127, 129, 192, 256, -1, -128 }) {
        DspNode node(variables_size);
        const Words real(8, 5), imag(8, 7);
        node.put(real_address, real);
        node.put(imag_address, imag);
        node.call(dsp_native("dsp.fft"),
                  { real_address, imag_address, static_cast<int16_t>(size) });
        ASSERT_EQ(node.errors.size(), 1u) << size;
        EXPECT_EQ(node.errors[0].kind, DspError::Kind::node_specific);
        EXPECT_NE(node.errors[0].message.find("dsp.fft"), std::string::npos);
        EXPECT_EQ(node.errors[0].pc, DspNode::call_pc);
        EXPECT_TRUE(node.stopped());
        EXPECT_EQ(node.get(real_address, 8), real);
        EXPECT_EQ(node.get(imag_address, 8), imag);
    }
}

TEST(DspMag, IsTheFloorOfTheSquareRootSaturatedTo32767)
{
    std::mt19937 generator(10);
    Words real = random_words(generator, 150);
    Words imag = random_words(generator, 150);
    // The extremes: the largest energy 2^31, exact squares, zero.
    const Words extreme_real = { INT16_MIN, INT16_MAX, 0, 3, -5, 23170, 23171, 0, -32768, 1 };
    const Words extreme_imag = { INT16_MIN, INT16_MAX, 0, 4, 12, 23170, 23170, -1, 0, 0 };
    real.insert(real.end(), extreme_real.begin(), extreme_real.end());
    imag.insert(imag.end(), extreme_imag.begin(), extreme_imag.end());
    const auto size = static_cast<uint16_t>(real.size());

    DspNode node(variables_size + 200);
    node.put(real_address, real);
    node.put(imag_address, imag);
    node.call(dsp_native("dsp.mag"),
              { dest_address, real_address, imag_address, static_cast<int16_t>(size) });
    ASSERT_TRUE(node.errors.empty());
    const auto magnitude = node.get(dest_address, size);
    for (uint16_t i = 0; i < size; ++i) {
        const double exact =
          std::floor(std::sqrt(double(real[i]) * real[i] + double(imag[i]) * imag[i]));
        EXPECT_EQ(magnitude[i], clamp_to_int16(exact)) << real[i] << ", " << imag[i];
    }
}

} // namespace
