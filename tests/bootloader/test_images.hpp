// Images the bootloader tests build from the documents rather than from a
// toolchain: a bootloader image laid out as linker/epuck-bootloader.gld and
// the fact sheet say (reset GOTO, IVT entry k at PC 0x04 + 2k leading to slot
// 1 + k of the application's table at 0x100, AIVT to its own code, code in
// its region), and the application of tests/bootloader/hex/application.hex
// with its descriptor.

#pragma once

#include <cstdint>

#include "tools/flash/hex_image.hpp"

namespace bootloader_test
{

inline constexpr uint32_t bootloader_base = 0x016F00;
inline constexpr uint32_t bootloader_reset = 0x016F40; // its start-up
inline constexpr uint32_t bootloader_code_end = bootloader_base + 0x200;

// The synthetic bootloader image, with one configuration word.
aseba::flash::ProgramImage bootloader_image();

// tests/bootloader/hex/application.hex with its descriptor (read from the
// repository root, where the tests run).
aseba::flash::ProgramImage application_image();

} // namespace bootloader_test
