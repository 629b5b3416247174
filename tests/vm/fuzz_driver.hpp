// One fuzzing case for the VM: memory sizes, a bytecode image and a stream
// of commands (runs with a budget, debug commands, incoming events,
// breakpoints, partial uploads), with the invariants that must hold
// whatever the bytes are. Shared by the GoogleTest fuzz test and the
// libFuzzer target (tests/fuzz/vm_fuzzer.cpp).

#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tests/support/vm_harness.hpp"

namespace vm_tests
{

struct FuzzCase {
    test_support::VmSizes sizes;
    std::vector<uint16_t> image;
    std::vector<uint8_t> commands;
};

// The largest step budget a fuzzing run gives vm_run: never 0, since a
// random image may loop forever.
inline constexpr uint16_t FUZZ_MAX_BUDGET = 64;

// What the cases reached, to show that the fuzzing is not shallow.
struct FuzzStats {
    unsigned messages[test_support::VmMessage::NODE_ERROR + 1] = {};
    unsigned runs = 0;
    unsigned run_step_comparisons = 0;
    unsigned uploads = 0;
    unsigned accepted_uploads = 0; // the verifier accepted the image, init is ready to run
};

// Runs `fuzz_case`; returns the first broken invariant, or "" when all held.
std::string run_fuzz_case(const FuzzCase &fuzz_case, FuzzStats *stats = nullptr);

// Reads a case from raw bytes (for libFuzzer): 4 size bytes, an image
// length byte, the image words, then commands.
FuzzCase fuzz_case_from_bytes(const uint8_t *data, size_t size);

} // namespace vm_tests
