// The harness image's VM with the e-puck's natives (REMOTE_NATIVES_EPUCK:
// the standard ones, then the DSP ones), as the natives' stand-ins
// (remote_our_node.cpp, remote_dsp_node.cpp) use it: one VM at a time, its
// memory that of a host-side vm_state.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

extern "C" {
#include "vm.h"
}

namespace dspic30_test
{

// The host's copy of the image's table: to find a native's index, and for
// the verifier's view of the bytecode (vm_state.natives).
extern const vm_native_table epuck_like_table;

// The place of `native` in epuck_like_table, if it is there.
std::optional<uint16_t> epuck_index(const vm_native &native);

// Gives the image `vm` (its memory as the host holds it); the image's VM
// answers as a node with id 1. A new vm_state is opened so, as it may lie
// where another was.
void open_epuck_vm(vm_state &vm);

// The same unless the image holds `vm` already: a test may compare two.
void use_epuck_vm(vm_state &vm);

// Runs native `index` of the image's table on `vm` (use_epuck_vm) as a
// NATIVE_CALL at `pc` would, with the words it pops, first popped first; fails the test
// when the image refuses.
void call_epuck_native(vm_state &vm,
                       uint16_t index,
                       uint16_t pc,
                       const std::vector<int16_t> &popped_words);

} // namespace dspic30_test
