// The DSP tests' helpers that need no VM (declared in dsp_node.hpp): a
// native's description, seeded random inputs and the exact expectations'
// rounding; apart from DspNode so that a test program can run its DspNode
// elsewhere (tests/ports/dspic30/remote_dsp_node.cpp: on the dsPIC30F).

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "dsp_node.hpp"
#include "tests/support/native_table.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "nat_words.h"
}

aseba::NativeFunction description_of(const vm_native &native)
{
    const test_support::OneModuleTable table(&native, 1, nat_words);
    return aseba::native_function(table, 0);
}

const vm_native &dsp_native(std::string_view name)
{
    static const vm_native_module *const modules[] = { NAT_DSP_MODULES };
    static const vm_native_table table = { modules, uint16_t(std::size(modules)), nat_words };
    for (uint16_t id = 0; id < vm_native_count(&table); ++id) {
        const vm_native *native = vm_native_at(&table, id);
        if (description_of(*native).name == name)
            return *native;
    }
    throw std::invalid_argument("no DSP native " + std::string(name));
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
