// What the simulated dsPIC30F's link (simulated_link.cpp) tells beyond
// remote_link.hpp's interface.

#pragma once

#include <cstdint>

namespace qemu_test
{

// The instruction cycles the harness image has run so far (0 before it
// started): the cost of the tests on the chip.
uint64_t simulated_chip_cycles();

} // namespace qemu_test
