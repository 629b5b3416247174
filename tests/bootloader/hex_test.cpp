// The Microchip Intel HEX reader and writer of tools/flash on hand-written
// files (tests/bootloader/hex/): the values expected below are read off the
// records by hand, following the fact sheet §4.4 (4 bytes per instruction,
// byte address = 2 x PC address), and the descriptor's CRC is computed here
// bit by bit from the CRC-16/XMODEM definition.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "tests/bootloader/xmodem.hpp"
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
    // The configuration word is kept for the images a programmer writes:
    // hex 0x1F00000 (PC 0xF80000, FOSC) holds 03 C7.
    std::map<uint32_t, uint16_t> configuration{ { 0xF80000, 0xC703 } };
    EXPECT_EQ(image.configuration, configuration);
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
                  Corrupt{ "store_region.hex", "PC address 0x16380 is outside the application" },
                  Corrupt{ "bootloader_region.hex", "PC address 0x17F40 is outside" },
                  Corrupt{ "beyond_flash.hex", "PC address 0x80000 is outside" },
                  Corrupt{ "no_eof.hex", "no end-of-file record" },
                  Corrupt{ "after_eof.hex", "line 4: record after the end-of-file" },
                  Corrupt{ "bad_digit.hex", "line 3: not a hex digit" },
                  Corrupt{ "count_mismatch.hex", "byte count does not match" },
                  Corrupt{ "no_colon.hex", "must start with ':'" },
                  Corrupt{ "overlap.hex",
                           "line 5: PC address 0x204 was given already on line 4: records "
                           "overlap" }));

uint32_t instruction_of(const aseba::flash::Page &page, std::size_t index)
{
    return static_cast<uint32_t>(page.bytes[4 * index] | page.bytes[4 * index + 1] << 8 |
                                 page.bytes[4 * index + 2] << 16);
}

TEST(Pages, CoverTheApplicationFromRowFourAndTheDescriptor)
{
    ProgramImage image = read("application.hex");
    aseba::flash::add_application_descriptor(image);
    auto pages = aseba::flash::make_pages(image);
    // Rows 0-3 are the bootloader's: the code from PC 0x100 up to 0x5C0 is
    // rows 4..23, then the descriptor's row, the last below the store.
    ASSERT_EQ(pages.size(), 21u);
    EXPECT_EQ(pages[0].number, 4);
    EXPECT_EQ(pages[19].number, 23);
    EXPECT_EQ(pages[20].number, BOOT_DESCRIPTOR_ADDRESS / 0x40);
    EXPECT_EQ(BOOT_DESCRIPTOR_ADDRESS, 0x16340u);
    // Page 4 is PC 0x100: the GOTO table, 00 02 04 00 = GOTO 0x200 ...
    EXPECT_EQ(instruction_of(pages[0], 0), 0x040200u);
    EXPECT_EQ(instruction_of(pages[0], 2), 0x040300u);
    EXPECT_EQ(pages[0].bytes[3], 0x00);
    // Page 8 is PC 0x200: 56 34 12 00 EF CD AB 00 ...
    EXPECT_EQ(pages[4].bytes[0], 0x56);
    EXPECT_EQ(pages[4].bytes[2], 0x12);
    EXPECT_EQ(pages[4].bytes[6], 0xAB);
    EXPECT_EQ(pages[4].bytes[16], 0xFF); // PC 0x208: nothing there, erased
    EXPECT_EQ(pages[4].bytes[19], 0x00);
    // The descriptor: magic, entry 0x100 (the reset slot), end after PC
    // 0x5C0, and the CRC of every instruction of [0x100, 0x5C2), 3 bytes
    // each, low first, erased where the file has none.
    const auto &descriptor = pages[20];
    EXPECT_EQ(instruction_of(descriptor, 0), 0xA5EB01u);
    EXPECT_EQ(instruction_of(descriptor, 1), 0x100u);
    EXPECT_EQ(instruction_of(descriptor, 2), 0x5C2u);
    std::map<uint32_t, uint32_t> code{ { 0x100, 0x040200 }, { 0x102, 0 },
                                       { 0x104, 0x040300 }, { 0x106, 0 },
                                       { 0x200, 0x123456 }, { 0x202, 0xABCDEF },
                                       { 0x204, 0 },        { 0x206, 0xFE0001 },
                                       { 0x5C0, 0x332211 } };
    std::vector<uint8_t> bytes;
    for (uint32_t pc = 0x100; pc < 0x5C2; pc += 2) {
        uint32_t value = code.count(pc) ? code[pc] : 0xFFFFFF;
        for (int b = 0; b < 3; b++)
            bytes.push_back(static_cast<uint8_t>(value >> (8 * b)));
    }
    EXPECT_EQ(instruction_of(descriptor, 3), bootloader_test::crc_xmodem(bytes));
}

TEST(Pages, AnApplicationWithoutResetSlotHasNoDescriptor)
{
    ProgramImage image;
    image.instructions[0x200] = 0x123456;
    EXPECT_THROW(aseba::flash::add_application_descriptor(image), HexError);
}

TEST(Pages, AnImageWithVectorsOfItsOwnIsRefused)
{
    ProgramImage image = read("good.hex"); // a reset GOTO at PC 0
    try {
        aseba::flash::add_application_descriptor(image);
        FAIL() << "accepted";
    } catch (const HexError &error) {
        EXPECT_NE(std::string(error.what()).find("below the application's start"),
                  std::string::npos)
          << error.what();
    }
}

TEST(Pages, TheEntryCanBeGivenForASyntheticImage)
{
    ProgramImage image;
    image.instructions[0x100] = 0x000000; // NOP
    image.instructions[0x102] = 0x040102; // GOTO 0x102
    image.instructions[0x104] = 0x000000;
    aseba::flash::add_application_descriptor(image, 0x102);
    EXPECT_EQ(image.instructions.at(BOOT_DESCRIPTOR_ADDRESS + 2), 0x102u);
    EXPECT_EQ(image.instructions.at(BOOT_DESCRIPTOR_ADDRESS + 4), 0x106u); // end
    auto pages = aseba::flash::make_pages(image);
    ASSERT_EQ(pages.size(), 2u);
    EXPECT_EQ(pages[0].number, 4);
}

TEST(Pages, AnEntryOutsideTheApplicationIsRefused)
{
    for (uint32_t entry : { 0x0u, 0xFEu, 0x101u, 0x5C2u }) {
        ProgramImage image = read("application.hex");
        EXPECT_THROW(aseba::flash::add_application_descriptor(image, entry), HexError) << entry;
    }
}

TEST(Pages, CodeInTheDescriptorRowIsRefused)
{
    ProgramImage image = read("application.hex");
    image.instructions[BOOT_DESCRIPTOR_ADDRESS + 0x3E] = 0x123456;
    EXPECT_THROW(aseba::flash::add_application_descriptor(image), HexError);
}

TEST(HexWriter, WritesRecordsAsTheHandMadeFile)
{
    // written.hex, by hand: five instructions from PC 0x104 split at the
    // 16-byte boundary (hex 0x210), one after a gap, one in the second 64 KB
    // of hex addresses, and FBORPOR (PC 0xF80004) = 0xFF7F.
    ProgramImage image;
    image.instructions = { { 0x104, 0x111111 },  { 0x106, 0x222222 }, { 0x108, 0x333333 },
                           { 0x10A, 0x444444 },  { 0x10C, 0x555555 }, { 0x120, 0x0000AA },
                           { 0x11000, 0xFFFFFF } };
    image.configuration[0xF80004] = 0xFF7F;
    EXPECT_EQ(aseba::flash::write_microchip_hex(image), read_text("written.hex"));
}

TEST(HexWriter, ReadingWhatItWroteGivesTheSameImage)
{
    ProgramImage image = read("application.hex");
    aseba::flash::add_application_descriptor(image);
    ProgramImage again =
      aseba::flash::read_microchip_hex(aseba::flash::write_microchip_hex(image), 0x18000);
    EXPECT_EQ(again.instructions, image.instructions);
    EXPECT_EQ(again.configuration, image.configuration);

    // Scattered runs over the whole flash, across 64 KB of hex addresses.
    std::mt19937 random(7);
    ProgramImage scattered;
    for (int run = 0; run < 200; run++) {
        uint32_t pc = (random() % 0xC000) * 2;
        for (uint32_t i = 0, length = random() % 40; i < length && pc < 0x18000; i++, pc += 2)
            scattered.instructions[pc] = random() & 0xFFFFFF;
    }
    scattered.configuration = { { 0xF80000, 0xC706 }, { 0xF8000A, 0xFFFF } };
    again = aseba::flash::read_microchip_hex(aseba::flash::write_microchip_hex(scattered), 0x18000);
    EXPECT_EQ(again.instructions, scattered.instructions);
    EXPECT_EQ(again.configuration, scattered.configuration);
}

// What the bootloader will check once the image is written: the checks of
// `aseba flash` before it reboots any robot.
TEST(ApplicationCheck, AcceptsWhatTheBootloaderAccepts)
{
    ProgramImage image = read("application.hex");
    aseba::flash::add_application_descriptor(image);
    EXPECT_NO_THROW(aseba::flash::check_application_image(image));
}

TEST(ApplicationCheck, RefusesWhatTheBootloaderWouldRefuse)
{
    const ProgramImage good = [] {
        ProgramImage image = read("application.hex");
        aseba::flash::add_application_descriptor(image);
        return image;
    }();
    auto descriptor = [](ProgramImage &image, uint32_t index) -> uint32_t & {
        return image.instructions[BOOT_DESCRIPTOR_ADDRESS + 2 * index];
    };
    struct Case {
        const char *what;
        std::function<void(ProgramImage &)> change;
        const char *message;
    };
    const Case cases[] = {
        { "data that differ from the CRC",
          [](ProgramImage &image) { image.instructions[0x202] ^= 1; },
          "the descriptor's CRC is" },
        { "a CRC that differs from the data",
          [&](ProgramImage &image) { descriptor(image, BOOT_DESCRIPTOR_CRC_INDEX) ^= 0x8000; },
          "the descriptor's CRC is" },
        { "an instruction the file lacks, now given",
          [](ProgramImage &image) { image.instructions[0x300] = 0xFFFFFE; },
          "the descriptor's CRC is" },
        { "no descriptor",
          [&](ProgramImage &image) { descriptor(image, BOOT_DESCRIPTOR_MAGIC_INDEX) = 0; },
          "no application descriptor" },
        { "an end beyond the pages written",
          [&](ProgramImage &image) { descriptor(image, BOOT_DESCRIPTOR_END_INDEX) = 0x700; },
          "the descriptor's end 0x700" },
        { "an odd end",
          [&](ProgramImage &image) { descriptor(image, BOOT_DESCRIPTOR_END_INDEX) = 0x5C1; },
          "the descriptor's end 0x5C1" },
        { "an entry below the application",
          [&](ProgramImage &image) { descriptor(image, BOOT_DESCRIPTOR_ENTRY_INDEX) = 0xFE; },
          "the descriptor's entry 0xFE" },
    };
    for (const Case &bad : cases) {
        ProgramImage image = good;
        bad.change(image);
        try {
            aseba::flash::check_application_image(image);
            ADD_FAILURE() << bad.what << ": accepted";
        } catch (const HexError &error) {
            EXPECT_NE(std::string(error.what()).find(bad.message), std::string::npos)
              << bad.what << ": " << error.what();
        }
    }
}

// The pages asebacmd whex writes, as its BootloaderInterface::writeHex
// builds them from a HEX file: a page for each page the file has data in,
// zeros where the file has none, pages without data not written at all.
std::map<uint16_t, std::vector<uint8_t>> reference_tool_pages(const std::string &hex_text)
{
    ProgramImage read_back = aseba::flash::read_microchip_hex(hex_text, 0x18000);
    std::map<uint16_t, std::vector<uint8_t>> pages;
    for (const auto &[pc, value] : read_back.instructions) {
        uint32_t byte_address = pc * 2;
        auto &page = pages[uint16_t(byte_address / aseba::flash::page_bytes)];
        page.resize(aseba::flash::page_bytes, 0);
        size_t at = byte_address % aseba::flash::page_bytes;
        for (size_t b = 0; b < 3; b++)
            page[at + b] = uint8_t(value >> (8 * b));
    }
    return pages;
}

// XC16 images have unprogrammed words inside the application: a HEX file
// with such gaps makes asebacmd write zeros (or nothing) where the
// descriptor's CRC expects erased words, and the robot stays in its
// bootloader. fill_pages, which epuck-image applies, leaves no gap: the
// reference's pages are then exactly the ones `aseba flash` writes.
TEST(FilledPages, AsebacmdWritesWhatTheDescriptorExpects)
{
    ProgramImage image = read("application.hex");
    aseba::flash::add_application_descriptor(image);
    auto expected = aseba::flash::make_pages(image);

    auto with_gaps = reference_tool_pages(aseba::flash::write_microchip_hex(image));
    EXPECT_NE(with_gaps.size(), expected.size()) << "pages without data are skipped";

    ProgramImage filled = aseba::flash::fill_pages(image);
    EXPECT_NO_THROW(aseba::flash::check_application_image(filled));
    auto written = reference_tool_pages(aseba::flash::write_microchip_hex(filled));
    ASSERT_EQ(written.size(), expected.size());
    for (const auto &page : expected) {
        ASSERT_TRUE(written.count(page.number)) << "page " << page.number;
        EXPECT_TRUE(std::equal(page.bytes.begin(), page.bytes.end(), written[page.number].begin()))
          << "page " << page.number;
    }
    EXPECT_EQ(aseba::flash::make_pages(filled).size(), expected.size());
}

} // namespace
