// A VM under test: its memory (with guard words around every array, so that
// a stray write shows, and under AddressSanitizer a stray read too), a log of
// every message it sends, and a few tiny native functions that exercise the
// NATIVE_CALL mechanism.

#pragma once

#include <cstdint>
#include <string>
#include <vector>

extern "C" {
#include "vm/vm.h"
}

namespace test_support
{

struct VmMessage {
    enum Kind { EMIT, STATE, KILLED, ARRAY_ACCESS, DIVISION_BY_ZERO, NODE_ERROR } kind = EMIT;
    uint16_t pc = 0;              // or the event id of an EMIT
    uint16_t flags = 0;           // STATE only
    uint16_t size = 0;            // ARRAY_ACCESS only
    uint16_t index = 0;           // ARRAY_ACCESS only
    std::vector<int16_t> payload; // EMIT only
    std::string text;             // NODE_ERROR only

    bool operator==(const VmMessage &other) const = default;
};

// One line, e.g. "error array_access pc=9 size=3 index=65535".
std::string describe(const VmMessage &message);

struct VmSizes {
    uint16_t bytecode = 256;
    uint16_t variables = 64;
    uint16_t stack = 32;
    uint16_t args = 32;
};

// The natives every harness VM has, in NATIVE_CALL order. Arguments are
// variable addresses except the sizes; the stack contract is bytecode.md §9.
enum TestNative {
    NATIVE_SUBTRACT,     // (dest, a, b): V[dest] = V[a] - V[b]
    NATIVE_FILL,         // (dest, value, size): V[dest .. +size] = V[value] (math.fill's contract)
    NATIVE_FAIL,         // (): stops the VM with NODE_SPECIFIC_ERROR "test failure"
    NATIVE_REACH,        // (address, length as a value): V[address .. +length] = 7
    NATIVE_YIELD,        // (): clears EVENT_RUNNING, as an interrupt may (bytecode.md §6)
    NATIVE_UNUSED_FIRST, // 5 .. 10: like NATIVE_FAIL, only to give the table 12 entries
    NATIVE_STAT = 11,    // (src, min, max, mean, size): math.stat's contract; the mean is
                         // the sum divided by size, truncated; written min, max, mean
    TEST_NATIVE_COUNT
};
extern const char test_native_failure_text[];

// The table of the natives above, the one a harness VM gets by default.
const vm_native_table &test_native_table();

class VmHarness
{
  public:
    explicit VmHarness(const VmSizes &sizes = VmSizes(),
                       uint16_t node_id = 1,
                       const vm_native_table &natives = test_native_table());
    VmHarness(const VmHarness &) = delete;
    VmHarness &operator=(const VmHarness &) = delete;
    ~VmHarness();

    vm_state vm;
    std::vector<VmMessage> log;

    // SET_BYTECODE of `words` at 0, then clears the log.
    void load(const std::vector<uint16_t> &words);

    uint16_t *bytecode()
    {
        return bytecode_.data() + GUARD_WORDS;
    }
    int16_t *variables()
    {
        return variables_.data() + GUARD_WORDS;
    }
    int16_t *stack()
    {
        return stack_.data() + GUARD_WORDS;
    }
    const VmSizes &sizes() const
    {
        return sizes_;
    }

    // Whether every guard word around the three arrays still holds its pattern.
    bool guards_intact() const;

  private:
    void poison_all_guards(bool poisoned) const;

    static constexpr size_t GUARD_WORDS = 8;
    static constexpr uint16_t GUARD_PATTERN = 0xA5C3;

    VmSizes sizes_;
    std::vector<uint16_t> bytecode_;
    std::vector<int16_t> variables_;
    std::vector<int16_t> stack_;
};

} // namespace test_support
