// The bootloader tests' images (see test_images.hpp).

#include "tests/bootloader/test_images.hpp"

namespace bootloader_test
{

using aseba::flash::ProgramImage;

ProgramImage bootloader_image()
{
    // Fact sheet §1.1, §1.7: 62 vectors, the IVT at 0x04, the AIVT at 0x84.
    constexpr uint32_t interrupt_count = 62, ivt_base = 0x04, aivt_base = 0x84;
    constexpr uint32_t goto_opcode = 0x040000;
    constexpr uint32_t fosc_address = 0xF80000;
    constexpr uint32_t fosc_factory_value = 0xC706; // fact sheet §1.5
    ProgramImage image;
    image.instructions[0x0] = goto_opcode | (bootloader_reset & 0xFFFF);
    image.instructions[0x2] = bootloader_reset >> 16;
    for (uint32_t k = 0; k < interrupt_count; k++) {
        image.instructions[ivt_base + 2 * k] = 0x100 + 4 * (1 + k);
        image.instructions[aivt_base + 2 * k] = bootloader_base + 0x100;
    }
    for (uint32_t pc = bootloader_base; pc < bootloader_code_end; pc += 2)
        image.instructions[pc] = pc; // its code
    image.configuration[fosc_address] = fosc_factory_value;
    return image;
}

ProgramImage application_image()
{
    ProgramImage image =
      aseba::flash::read_microchip_hex_file("tests/bootloader/hex/application.hex", 0x16340);
    aseba::flash::add_application_descriptor(image);
    return image;
}

} // namespace bootloader_test
