// A VM state over memory owned by the test, to call our natives directly as
// the VM's NATIVE_CALL does, and a record of the errors they report.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tools/compiler/target.hpp"

extern "C" {
#include "nat_standard.h"
#include "vm.h"
}

// The standard native named `name` ("math.copy"), to call one alone: the
// library exports only its modules (nat_standard.h).
const vm_native &standard_native(std::string_view name);

// What `native`, of the standard or DSP natives, says of itself: its packed
// description expanded with their words (nat_words.h).
aseba::NativeFunction description_of(const vm_native &native);

// The VM's callbacks of an OurNode (its context): the errors go to its
// `errors`, the rest is ignored.
extern const vm_callbacks our_node_callbacks;

// One error message the VM sent, with its protocol payload.
struct ErrorReport {
    enum class Kind { array_access, division_by_zero, node_specific };
    Kind kind;
    uint16_t pc;
    uint16_t size = 0;   // array_access only
    uint16_t index = 0;  // array_access only
    std::string message; // node_specific only

    bool operator==(const ErrorReport &) const = default;
};

class OurNode
{
  public:
    // The pc the VM would be at when it runs the NATIVE_CALL.
    static constexpr uint16_t call_pc = 321;

    explicit OurNode(uint16_t variables_size);

    // Calls `native` with the words it pops, first popped first (bytecode.md
    // §9), inside a running event. The count must be the native's stack_words.
    void call(const vm_native &native, const std::vector<int16_t> &popped_words);

    // Writes `values` from `address` on; reads `count` words from `address`.
    void put(uint16_t address, const std::vector<int16_t> &values);
    std::vector<int16_t> get(uint16_t address, uint16_t count) const;

    // Runs `bytecode` (handling only `init`, 0xFFFF) with our VM to its end.
    void run_init(const std::vector<uint16_t> &bytecode);

    // Whether the last call stopped the VM (an error).
    bool stopped() const
    {
        return (vm.flags & VM_FLAG_EVENT_ACTIVE) == 0;
    }

    std::vector<int16_t> variables;
    std::vector<ErrorReport> errors;
    vm_state vm;

  private:
    std::vector<uint16_t> bytecode_;
    std::vector<int16_t> stack_;
};
