// A VM over memory owned by the test, whose native table is the e-puck's
// order (standard natives, then the DSP ones), to call the DSP natives
// directly as NATIVE_CALL does or through bytecode; records the errors.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "tools/compiler/target.hpp"

extern "C" {
#include "nat_dsp.h"
#include "nat_standard.h"
#include "vm.h"
}

using Words = std::vector<int16_t>;

// The DSP native named `name` ("dsp.fft"), to call one alone: the library
// exports only its modules (nat_dsp.h).
const vm_native &dsp_native(std::string_view name);

// What `native`, of the standard or DSP natives, says of itself: its packed
// description expanded with their words (nat_words.h).
aseba::NativeFunction description_of(const vm_native &native);

// One error message the VM sent.
struct DspError {
    enum class Kind { array_access, division_by_zero, node_specific };
    Kind kind;
    uint16_t pc;
    std::string message; // node_specific only
};

class DspNode
{
  public:
    // The pc the VM is at when a direct call runs the NATIVE_CALL.
    static constexpr uint16_t call_pc = 123;
    // NATIVE_CALL id of the first DSP native in this node's table.
    static inline const uint16_t first_dsp_id = vm_native_count(&nat_standard_table);

    // `args_size` words of `args` at VM_NAMED_ARGS receive event payloads.
    explicit DspNode(uint16_t variables_size,
                     uint16_t bytecode_words = 128,
                     uint16_t args_size = 0);

    // Calls `native` with the words it pops, first popped first (bytecode.md
    // §9), inside a running event. The count must be the native's stack_words.
    void call(const vm_native &native, const std::vector<int16_t> &popped_words);

    void put(uint16_t address, const Words &values);
    Words get(uint16_t address, uint16_t count) const;

    // Runs `code` as the handler of `init` (0xFFFF) with our VM to its end.
    void run_init(const std::vector<uint16_t> &code);

    // Loads a whole compiled image (event table, then code) and runs `init`.
    void load_and_run_init(const std::vector<uint16_t> &image);

    // Whether the VM was stopped (an error).
    bool stopped() const
    {
        return (vm.flags & VM_FLAG_EVENT_ACTIVE) == 0;
    }

    std::vector<int16_t> variables;
    std::vector<DspError> errors;
    vm_state vm;

  private:
    std::vector<uint16_t> bytecode_;
    std::vector<int16_t> stack_;
};

// Uniform random int16 words in [low, high], from a seeded generator.
Words random_words(std::mt19937 &generator,
                   size_t count,
                   int low = INT16_MIN,
                   int high = INT16_MAX);

// value clamped to the int16 range (the expectation of a saturating result).
int16_t clamp_to_int16(double value);

// sum / 2^shift rounded half up, as an exact expectation for integer sums.
double round_half_up(double sum, int shift);
