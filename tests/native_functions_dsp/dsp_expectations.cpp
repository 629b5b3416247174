// The DSP tests' helpers that need no VM (declared in dsp_node.hpp): a
// native's description, seeded random inputs and the exact expectations'
// rounding; apart from DspNode so that a test program can run its DspNode
// elsewhere (tests/ports/dspic30/remote_dsp_node.cpp: on the dsPIC30F).

#include <algorithm>
#include <cmath>

#include "dsp_node.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "nat_words.h"
}

aseba::NativeFunction description_of(const vm_native &native)
{
    const vm_native list[] = { native };
    return aseba::native_function(vm_native_table{ list, 1, nat_words }, 0);
}

Words random_words(std::mt19937 &generator, size_t count, int low, int high)
{
    std::uniform_int_distribution<int> distribution(low, high);
    Words words(count);
    for (auto &word : words)
        word = static_cast<int16_t>(distribution(generator));
    return words;
}

int16_t clamp_to_int16(double value)
{
    return static_cast<int16_t>(std::clamp(value, double(INT16_MIN), double(INT16_MAX)));
}

double round_half_up(double sum, int shift)
{
    return std::floor(sum / std::ldexp(1.0, shift) + 0.5);
}
