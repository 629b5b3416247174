// The factory Tiny Bootloader's row packets (tools/flash/tiny_bootloader.hpp)
// checked byte by byte against the fact sheet §4.2-4.3.

#include <gtest/gtest.h>

#include <fstream>
#include <numeric>
#include <sstream>

#include "tools/flash/tiny_bootloader.hpp"

namespace
{

using aseba::flash::ProgramImage;

ProgramImage good_image()
{
    std::ifstream file("tests/bootloader/hex/good.hex", std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return aseba::flash::read_microchip_hex(text.str(), 0x17F00);
}

TEST(TinyBootloader, SendsEveryRowThenTheTrampoline)
{
    auto packets = aseba::flash::tiny_bootloader_packets(good_image(), 0x1234);
    // good.hex reaches PC 0x5C0: rows 0..23, then the row at 0x017F00.
    ASSERT_EQ(packets.size(), 25u);
    for (std::size_t i = 0; i < packets.size(); i++) {
        const auto &packet = packets[i];
        uint32_t address = packet[0] | packet[1] << 8 | packet[2] << 16;
        EXPECT_EQ(address, i + 1 < packets.size() ? i * 0x40 : 0x017F00u);
        EXPECT_EQ(packet[3], 0x60);
        unsigned sum = std::accumulate(packet.begin(), packet.end(), 0u);
        EXPECT_EQ(sum % 256, 0u) << "packet " << i;
    }
}

TEST(TinyBootloader, RedirectsTheResetVectorAndKeepsTheCode)
{
    auto packets = aseba::flash::tiny_bootloader_packets(good_image(), 7);
    // GOTO 0x017F40 without phantom bytes: 40 7F 04, 01 00 00 (§4.1).
    std::vector<uint8_t> vector(packets[0].begin() + 4, packets[0].begin() + 10);
    EXPECT_EQ(vector, (std::vector<uint8_t>{ 0x40, 0x7F, 0x04, 0x01, 0x00, 0x00 }));
    // PC 4 = 0x000300 (good.hex), the rest of the row erased.
    EXPECT_EQ(packets[0][10], 0x00);
    EXPECT_EQ(packets[0][11], 0x03);
    EXPECT_EQ(packets[0][12], 0x00);
    EXPECT_EQ(packets[0][16], 0xFF);
    // Row 8 (PC 0x200) starts with 0x123456.
    EXPECT_EQ(packets[8][4], 0x56);
    EXPECT_EQ(packets[8][5], 0x34);
    EXPECT_EQ(packets[8][6], 0x12);
}

TEST(TinyBootloader, TrampolineHoldsTheIdAndAGotoToTheImageEntry)
{
    auto packets = aseba::flash::tiny_bootloader_packets(good_image(), 0x1234);
    const auto &row = packets.back();
    // 0x017F36 is instruction 27 of the row: payload bytes 81..83.
    EXPECT_EQ(row[4 + 81], 0x34);
    EXPECT_EQ(row[4 + 82], 0x12);
    EXPECT_EQ(row[4 + 83], 0x00);
    // 0x017F38/0x017F3A: GOTO 0x000200, good.hex's reset target.
    std::vector<uint8_t> jump(row.begin() + 4 + 84, row.begin() + 4 + 90);
    EXPECT_EQ(jump, (std::vector<uint8_t>{ 0x00, 0x02, 0x04, 0x00, 0x00, 0x00 }));
    // Everything else erased, the Tiny Bootloader's code (0x017F40 on) included.
    for (std::size_t i = 0; i < 81; i++)
        EXPECT_EQ(row[4 + i], 0xFF) << i;
    for (std::size_t i = 90; i < 96; i++)
        EXPECT_EQ(row[4 + i], 0xFF) << i;
}

TEST(TinyBootloader, RefusesImagesItCannotInstall)
{
    ProgramImage no_goto;
    no_goto.instructions[0x200] = 1;
    EXPECT_THROW(aseba::flash::tiny_bootloader_packets(no_goto, 1), aseba::flash::HexError);
    ProgramImage over_tiny = good_image();
    over_tiny.instructions[0x017F40] = 0;
    EXPECT_THROW(aseba::flash::tiny_bootloader_packets(over_tiny, 1), aseba::flash::HexError);
}

TEST(TinyBootloader, EndsWithTheLedTimeAndTheDoneMarker)
{
    auto end = aseba::flash::tiny_bootloader_end(0x95);
    EXPECT_EQ(end, (std::array<uint8_t, 4>{ 0x95, 0x00, 0x00, 0xFF }));
}

} // namespace
