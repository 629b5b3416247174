// The Microchip Intel HEX reader of tools/flash on hand-written files
// (tests/bootloader/hex/): the values expected below are read off the
// records by hand, following the fact sheet §4.4 (4 bytes per instruction,
// byte address = 2 x PC address).

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tools/flash/hex_image.hpp"

extern "C" {
#include "bootloader/boot_application.h"
}

namespace
{

using aseba::flash::HexError;
using aseba::flash::ProgramImage;

std::string read_text(const std::string &name)
{
    std::ifstream file("tests/bootloader/hex/" + name, std::ios::binary);
    EXPECT_TRUE(file.good()) << name;
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

ProgramImage read(const std::string &name)
{
    return aseba::flash::read_microchip_hex(read_text(name), BOOT_DESCRIPTOR_ADDRESS);
}

TEST(Hex, ReadsProgramWordsAndSkipsEepromAndConfiguration)
{
    ProgramImage image = read("good.hex");
    std::map<uint32_t, uint32_t> expected{
        { 0x000, 0x040200 }, { 0x002, 0x000000 }, // GOTO 0x000200
        { 0x004, 0x000300 }, { 0x006, 0x000302 }, // hex 0x0008: the first vectors
        { 0x200, 0x123456 }, { 0x202, 0xABCDEF }, { 0x204, 0x000000 },
        { 0x206, 0xFE0001 }, { 0x5C0, 0x332211 }, // hex 0x0B80
    };
    EXPECT_EQ(image.instructions, expected);
    EXPECT_EQ(image.skipped_bytes, 8u); // one EEPROM word, one configuration word
}

struct Corrupt {
    const char *file;
    const char *message; // a part of the error text
};

class CorruptHex : public testing::TestWithParam<Corrupt>
{
};

TEST_P(CorruptHex, IsRejectedWithAClearError)
{
    try {
        read(GetParam().file);
        FAIL() << GetParam().file << " was accepted";
    } catch (const HexError &error) {
        EXPECT_NE(std::string(error.what()).find(GetParam().message), std::string::npos)
          << error.what();
    }
}

INSTANTIATE_TEST_SUITE_P(
  Files,
  CorruptHex,
  testing::Values(Corrupt{ "bad_checksum.hex", "line 3: bad checksum" },
                  Corrupt{ "bad_type.hex", "line 3: unsupported record type 2" },
                  Corrupt{ "start_address_type.hex", "unsupported record type 5" },
                  Corrupt{ "odd_length.hex", "whole 4-byte instructions" },
                  Corrupt{ "unaligned.hex", "whole 4-byte instructions (address 0x402" },
                  Corrupt{ "phantom.hex", "non-zero phantom byte at PC address 0x200" },
                  Corrupt{ "store_region.hex", "PC address 0x16F00 is outside the application" },
                  Corrupt{ "bootloader_region.hex", "PC address 0x17F40 is outside" },
                  Corrupt{ "beyond_flash.hex", "PC address 0x80000 is outside" },
                  Corrupt{ "no_eof.hex", "no end-of-file record" },
                  Corrupt{ "after_eof.hex", "line 4: record after the end-of-file" },
                  Corrupt{ "bad_digit.hex", "line 3: not a hex digit" },
                  Corrupt{ "count_mismatch.hex", "byte count does not match" },
                  Corrupt{ "no_colon.hex", "must start with ':'" }));

TEST(Pages, CoverTheCodeAndTheDescriptor)
{
    ProgramImage image = read("good.hex");
    aseba::flash::add_application_descriptor(image);
    auto pages = aseba::flash::make_pages(image);
    // Code up to PC 0x5C0 is rows 0..23, then the descriptor's row.
    ASSERT_EQ(pages.size(), 25u);
    EXPECT_EQ(pages[23].number, 23);
    EXPECT_EQ(pages[24].number, BOOT_DESCRIPTOR_ADDRESS / 0x40);
    // Page 8 is PC 0x200: 56 34 12 00 EF CD AB 00 ...
    EXPECT_EQ(pages[8].bytes[0], 0x56);
    EXPECT_EQ(pages[8].bytes[2], 0x12);
    EXPECT_EQ(pages[8].bytes[3], 0x00);
    EXPECT_EQ(pages[8].bytes[6], 0xAB);
    EXPECT_EQ(pages[8].bytes[16], 0xFF); // PC 0x208: nothing there, erased
    EXPECT_EQ(pages[8].bytes[19], 0x00);
    // The descriptor: magic, entry 0x200 (the GOTO), end after PC 0x5C0.
    const auto &descriptor = pages[24].bytes;
    EXPECT_EQ(descriptor[0] | descriptor[1] << 8 | descriptor[2] << 16, 0xA5EB01);
    EXPECT_EQ(descriptor[4] | descriptor[5] << 8 | descriptor[6] << 16, 0x200);
    EXPECT_EQ(descriptor[8] | descriptor[9] << 8 | descriptor[10] << 16, 0x5C2);
}

TEST(Pages, AnImageWithoutResetGotoHasNoDescriptor)
{
    ProgramImage image;
    image.instructions[0x200] = 0x123456;
    EXPECT_THROW(aseba::flash::add_application_descriptor(image), HexError);
}

TEST(Pages, TheEntryCanBeGivenForAnImageThatHoldsTheBootloader)
{
    ProgramImage image = read("good.hex");
    image.instructions[0x17740] = 0x000000; // bootloader code above the store
    aseba::flash::add_application_descriptor(image, 0x100);
    EXPECT_EQ(image.instructions.at(BOOT_DESCRIPTOR_ADDRESS + 2), 0x100u);
    EXPECT_EQ(image.instructions.at(BOOT_DESCRIPTOR_ADDRESS + 4), 0x5C2u); // end of the application
}

TEST(Pages, CodeInTheDescriptorRowIsRefused)
{
    ProgramImage image = read("good.hex");
    image.instructions[BOOT_DESCRIPTOR_ADDRESS + 0x3E] = 0x123456;
    EXPECT_THROW(aseba::flash::add_application_descriptor(image), HexError);
}

} // namespace
