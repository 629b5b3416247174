// dsp.fft exactly, not within a tolerance: the documented rounding (each
// butterfly output (a ± W b) / 2 rounded half up, W b rounded half up to an
// integer, Q15 twiddles, saturation) pinned by cases worked out by hand and
// by an independent model of the documented transform, compared bit for
// bit. The tolerance tests of dsp_fft_test.cpp cannot tell a butterfly that
// rounds half up from one that truncates; these tests can, and the last one
// proves it on such a fault (dsp_fft_truncating_mutant.c).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "dsp_node.hpp"

// dsp_fft_truncating_mutant.c: nat_dsp_fft.c's module, dsp.fft compiled
// with the fault.
extern "C" const vm_native_module nat_dsp_fft_truncating_mutant_module;

namespace
{

constexpr uint16_t real_address = 0;
constexpr uint16_t imag_address = 200;
constexpr uint16_t variables_size = 400;
const uint16_t fft_sizes[] = { 8, 16, 32, 64, 128 };

struct Spectrum {
    Words real;
    Words imag;
    bool operator==(const Spectrum &) const = default;
};

Spectrum run(const vm_native &fft, const Spectrum &input)
{
    DspNode node(variables_size);
    node.put(real_address, input.real);
    node.put(imag_address, input.imag);
    const auto size = static_cast<int16_t>(input.real.size());
    node.call(fft, { real_address, imag_address, size });
    return { node.get(real_address, size), node.get(imag_address, size) };
}

// --- the independent model -----------------------------------------------------

// value / 2^shift rounded half up, in exact integer arithmetic.
int64_t round_half_up_shift(int64_t value, int shift)
{
    const int64_t divisor = int64_t{ 1 } << shift;
    // Floor division of value + divisor / 2.
    const int64_t shifted = value + divisor / 2;
    return shifted >= 0 ? shifted / divisor : -((-shifted + divisor - 1) / divisor);
}

int16_t saturate(int64_t value)
{
    return static_cast<int16_t>(std::clamp<int64_t>(value, INT16_MIN, INT16_MAX));
}

// The documented twiddle table: round(32768 cos) and round(32768 sin) of
// 2 pi j / 128, 1.0 clamped to 32767.
int64_t q15(double value)
{
    return std::min<int64_t>(32767, std::llround(32768 * value));
}

// The documented transform, written as its recursive definition (the
// native is iterative and in place): the half-size transforms of the even
// and odd samples, combined by butterflies that each halve.
Spectrum model_fft(const Spectrum &input)
{
    const size_t size = input.real.size();
    if (size == 1)
        return input;
    Spectrum even, odd;
    for (size_t n = 0; n < size; n += 2) {
        even.real.push_back(input.real[n]);
        even.imag.push_back(input.imag[n]);
        odd.real.push_back(input.real[n + 1]);
        odd.imag.push_back(input.imag[n + 1]);
    }
    even = model_fft(even);
    odd = model_fft(odd);
    Spectrum output{ Words(size), Words(size) };
    for (size_t k = 0; k < size / 2; ++k) {
        // W^k = exp(-2 pi i k / size) = cos - i sin of table entry k * 128 / size.
        const double angle = 2 * std::numbers::pi * double(k * 128 / size) / 128;
        const int64_t cosine = q15(std::cos(angle)), sine = q15(std::sin(angle));
        int64_t t_real = odd.real[k], t_imag = odd.imag[k];
        if (k != 0) { // W^0 is 1 exactly, not 32767 / 32768
            t_real = round_half_up_shift(odd.real[k] * cosine + odd.imag[k] * sine, 15);
            t_imag = round_half_up_shift(odd.imag[k] * cosine - odd.real[k] * sine, 15);
        }
        output.real[k] = saturate(round_half_up_shift(even.real[k] + t_real, 1));
        output.imag[k] = saturate(round_half_up_shift(even.imag[k] + t_imag, 1));
        output.real[k + size / 2] = saturate(round_half_up_shift(even.real[k] - t_real, 1));
        output.imag[k + size / 2] = saturate(round_half_up_shift(even.imag[k] - t_imag, 1));
    }
    return output;
}

// --- the exact cases --------------------------------------------------------------

std::string show(const Spectrum &spectrum)
{
    std::ostringstream text;
    for (size_t k = 0; k < spectrum.real.size(); ++k)
        text << (k ? " " : "") << spectrum.real[k] << (spectrum.imag[k] < 0 ? "" : "+")
             << spectrum.imag[k] << "i";
    return text.str();
}

// How `fft` departs from the exact cases; empty when it computes the
// documented transform.
std::vector<std::string> exact_mismatches(const vm_native &fft)
{
    std::vector<std::string> mismatches;
    auto check = [&](const std::string &what, const Spectrum &input, const Spectrum &expected) {
        const Spectrum got = run(fft, input);
        if (!(got == expected))
            mismatches.push_back(what + ": got " + show(got) + ", expected " + show(expected));
    };

    for (uint16_t size : fft_sizes) {
        const std::string n = "N = " + std::to_string(size);
        // By hand: a unit impulse x = (1, 0, ..., 0). Every butterfly that
        // meets it computes (1 ± 0) / 2 = 0.5, which rounds half up to 1,
        // and only ever meets 1s and 0s: every bin ends as exactly 1 (the
        // exact X[k] / N is 1 / N). A butterfly that truncated would give 0.
        Spectrum impulse{ Words(size, 0), Words(size, 0) };
        impulse.real[0] = 1;
        check(n + ", impulse 1", impulse, { Words(size, 1), Words(size, 0) });
        // (-1 ± 0) / 2 = -0.5 rounds half up to 0: every bin is 0.
        impulse.real[0] = -1;
        check(n + ", impulse -1", impulse, { Words(size, 0), Words(size, 0) });
        // The same on the imaginary part: i / 2 rounds to i.
        impulse.real[0] = 0;
        impulse.imag[0] = 1;
        check(n + ", impulse i", impulse, { Words(size, 0), Words(size, 1) });

        // Against the model: random inputs, full-scale ones (saturation),
        // and small odd values, where every halving has a half to round.
        std::mt19937 generator(size);
        for (int trial = 0; trial < 20; ++trial) {
            const int range = trial < 10 ? 23000 : trial < 15 ? 32768 : 3;
            Spectrum input{ random_words(generator, size, -range, range - 1),
                            random_words(generator, size, -range, range - 1) };
            check(n + ", random input " + std::to_string(trial), input, model_fft(input));
        }
    }
    return mismatches;
}

TEST(DspFftExact, MatchesTheHandWorkedCasesAndTheModelBitForBit)
{
    for (const std::string &mismatch : exact_mismatches(dsp_native("dsp.fft")))
        ADD_FAILURE() << mismatch;
}

// The proof that the exact cases catch the fault that the tolerance lets
// through: a butterfly that truncates (dsp_fft_truncating_mutant.c).
TEST(DspFftExact, CatchesAButterflyThatTruncatesInsteadOfRoundingHalfUp)
{
    const auto mismatches = exact_mismatches(nat_dsp_fft_truncating_mutant_module.natives[0]);
    EXPECT_FALSE(mismatches.empty()) << "the truncating butterfly passed every exact case";
    // The impulse, worked by hand, is enough on its own.
    EXPECT_TRUE(std::any_of(mismatches.begin(), mismatches.end(), [](const std::string &m) {
        return m.find("N = 8, impulse 1:") == 0;
    }));
}

} // namespace
