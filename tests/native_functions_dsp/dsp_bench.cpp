// bench-dsp: calls one DSP native once on fixed data, for instruction counts
// under callgrind (setup excluded by toggling collection on the native):
//   valgrind --tool=callgrind --toggle-collect=nat_dsp_fft_function bench-dsp fft
//   valgrind --tool=callgrind --toggle-collect=nat_dsp_fir_function bench-dsp fir
// fft: a 64-point FFT; fir: a 64-sample signal through a 32-tap FIR.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "dsp_node.hpp"

namespace
{

constexpr uint16_t fft_size = 64;
constexpr uint16_t fir_length = 64;
constexpr uint16_t fir_taps = 32;

} // namespace

int main(int argc, char **argv)
{
    const std::string which = argc > 1 ? argv[1] : "";
    DspNode node(512);
    std::mt19937 generator(1);
    if (which == "fft") {
        node.put(0, random_words(generator, fft_size, -20000, 20000));
        node.call(dsp_native("dsp.fft"), { 0, 128, fft_size });
    } else if (which == "fir") {
        node.put(0, random_words(generator, fir_length));
        node.put(128, random_words(generator, fir_taps, -1000, 1000));
        node.call(dsp_native("dsp.fir"), { 256, 0, 128, fir_length, fir_taps });
    } else {
        std::fprintf(stderr, "usage: bench-dsp fft|fir\n");
        return 2;
    }
    return node.errors.empty() ? 0 : 1;
}
