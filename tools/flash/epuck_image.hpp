// The two images `make dspic30` delivers, from the XC16 builds of the
// application (linker/epuck-app.gld) and of the Aseba bootloader
// (linker/epuck-bootloader.gld), laid out as robots/epuck/epuck_flash_layout.h says:
//
//   epuck-aseba.hex          the application and its descriptor: what the
//                            Aseba bootloader flashes (asebacmd whex)
//   epuck-aseba-factory.hex  the bootloader image, the application and its
//                            descriptor: the first installation, through the
//                            factory Tiny Bootloader or a programmer

#pragma once

#include "tools/flash/hex_image.hpp"

namespace aseba::flash
{

// Checks that `bootloader` is a bootloader image: instructions only in rows
// 0-3 and in [BOOT_LOADER_BASE, BOOT_LOADER_END), a reset GOTO into the
// latter, and IVT entry k leading to the application's table slot
// BOOT_TABLE_INTERRUPT_SLOT(k) for every k; throws HexError naming the first
// fault.
void check_bootloader_image(const ProgramImage &bootloader);

// The union of two images that do not overlap; throws HexError when both
// hold the same instruction address, or different values for one
// configuration word.
ProgramImage merge_images(const ProgramImage &first, const ProgramImage &second);

} // namespace aseba::flash
