// The camera driver against a simulated PO3030K / PO6030K: a register file
// on I2C at 0xDC that identifies itself in registers 0x00/0x01, receives the
// library's init table (hardware §3.5), and sends RGB565 rows.

#include "modelled_world.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <map>

extern "C" {
#include "robots/epuck/devices/epuck_camera.h"
}

namespace drivers_test
{
namespace
{

// RGB565 fields of the pixel the simulated camera sends at `pixel` of `row`.
struct Rgb {
    unsigned r, g, b;
};
Rgb pixel_colour(uint16_t row, unsigned pixel)
{
    return { (pixel + row) % 32, (2 * pixel + 1) % 64, 31 - pixel % 32 };
}
// Big-endian RGB565 on the wire: R5G3 first, then G3B5 (§3.5).
uint8_t pixel_byte(uint16_t row, uint16_t index)
{
    Rgb c = pixel_colour(row, index / 2);
    uint16_t word = uint16_t((c.r << 11) | (c.g << 5) | c.b);
    return index % 2 == 0 ? uint8_t(word >> 8) : uint8_t(word & 0xFF);
}

struct Camera : ::testing::Test {
    std::unique_ptr<hal_board> board = std::make_unique<hal_board>();
    ModelledWorld world;
    epuck_camera camera{};
    void SetUp() override
    {
        host_board_init(board.get(), nullptr, nullptr);
        world.camera_pixels = pixel_byte;
        world.attach(board.get());
    }
    void present(uint8_t id_high)
    {
        world.camera_present = true;
        world.camera_registers[0x00] = id_high;
        world.camera_registers[0x01] = 0x30;
    }
};

// Registers of the library's PO3030K table (§3.5) that do not depend on the
// window, the format or the subsampling.
const std::vector<std::pair<uint8_t, uint8_t>> po3030_fixed = {
    { 0x04, 0x03 }, { 0x05, 0x53 }, { 0x12, 0x02 }, { 0x13, 0x02 }, { 0x15, 0x10 }, { 0x16, 0x40 },
    { 0x17, 0x40 }, { 0x18, 0x40 }, { 0x19, 0x40 }, { 0x1A, 0x03 }, { 0x1B, 0xE6 }, { 0x1C, 0x00 },
    { 0x1E, 0x0A }, { 0x1F, 0x1B }, { 0x3B, 0x00 }, { 0x46, 0x80 }, { 0x48, 0x60 }, { 0x49, 0x96 },
    { 0x4A, 0x00 }, { 0x4B, 0x7D }, { 0x4C, 0x00 }, { 0x4F, 0x0A }, { 0x50, 0x70 }, { 0x59, 0x00 },
    { 0x5A, 0x00 }, { 0x5B, 0x00 }, { 0x5C, 0xAC }, { 0x5D, 0x02 }, { 0x97, 0x25 }, { 0x98, 0x25 },
    { 0x9B, 0x00 }, { 0x9C, 0x96 }, { 0xA9, 0x00 }, { 0xAA, 0x01 }, { 0xD4, 0x3C }, { 0xD5, 0x01 },
    { 0xD8, 0x80 },
};

uint16_t pair(const ModelledWorld &world, uint8_t high)
{
    return uint16_t((world.camera_registers[high] << 8) | world.camera_registers[high + 1]);
}

TEST_F(Camera, Po3030ReceivesTheLibraryTableForRgb565Qqvga)
{
    present(0x30);
    ASSERT_TRUE(epuck_camera_init(&camera, board.get()));
    EXPECT_EQ(epuck_camera_model_of(&camera), EPUCK_CAMERA_PO3030);
    // Reset: driven low, then high (§3.5).
    auto reset = world.changes_of(EPUCK_PIN_CAMERA_RESET);
    ASSERT_EQ(reset.size(), 2u);
    EXPECT_FALSE(reset[0].high);
    EXPECT_TRUE(reset[1].high);
    for (auto [reg, value] : po3030_fixed) {
        bool written = false;
        for (auto &write : world.camera_writes)
            written |= write.first == reg;
        EXPECT_TRUE(written) << "register 0x" << std::hex << int(reg);
        EXPECT_EQ(world.camera_registers[reg], value) << "register 0x" << std::hex << int(reg);
    }
    EXPECT_EQ(world.camera_registers[0x4E], 0x08); // RGB565
    EXPECT_EQ(world.camera_registers[0x20], 0x33); // QQVGA: the sensor subsamples 4×
    // A window 480 wide and high inside the 640 × 480 array, whose
    // origin is (210, 7); VSYNC framing the same rows.
    uint16_t x1 = pair(world, 0x08), x2 = pair(world, 0x0C);
    uint16_t y1 = pair(world, 0x0A), y2 = pair(world, 0x0E);
    EXPECT_EQ(x2 - x1, 480);
    EXPECT_EQ(y2 - y1, 480);
    EXPECT_GE(x1, 210);
    EXPECT_LE(x2, 210 + 640);
    EXPECT_GE(y1, 7);
    EXPECT_EQ(pair(world, 0xA5), y1);
    EXPECT_EQ(pair(world, 0xA7), y2);
}

TEST_F(Camera, Po6030WritesItsBankedRegisters)
{
    present(0x60);
    ASSERT_TRUE(epuck_camera_init(&camera, board.get()));
    EXPECT_EQ(epuck_camera_model_of(&camera), EPUCK_CAMERA_PO6030);
    // Follow register 0x03, the bank (§3.5): A = 0, B = 1.
    std::map<std::pair<int, uint8_t>, uint8_t> banked;
    int bank = 0;
    for (auto [reg, value] : world.camera_writes) {
        if (reg == 0x03)
            bank = value;
        else
            banked[{ bank, reg }] = value;
    }
    EXPECT_EQ((banked[{ 1, 0x38 }]), 0x08);        // RGB565
    EXPECT_EQ((banked[{ 1, 0x80 }]), 0x80);        // scale X: QQVGA
    EXPECT_EQ((banked[{ 1, 0x81 }]), 0x80);        // scale Y: QQVGA
    EXPECT_EQ((banked[{ 0, 0x90 }]) & 0xC0, 0xC0); // mirror (1, 1)
}

TEST_F(Camera, NoCameraNoLine)
{
    EXPECT_FALSE(epuck_camera_init(&camera, board.get()));
    EXPECT_EQ(epuck_camera_model_of(&camera), EPUCK_CAMERA_NONE);
    std::array<int16_t, 60> r{}, g{}, b{};
    EXPECT_FALSE(epuck_camera_capture(&camera, 50, r.data(), g.data(), b.data()));
}

TEST_F(Camera, UnknownCameraIsNotConfigured)
{
    present(0x80); // a PO8030D, which the driver does not know
    EXPECT_FALSE(epuck_camera_init(&camera, board.get()));
    EXPECT_TRUE(world.camera_writes.empty());
}

// 60 pixels from a 120-pixel row, every second one, scaled to 0..93 (red,
// blue: ×3) and 0..94 (green: ×3/2) as the upstream firmware does (§3.5).
TEST_F(Camera, LineIsEverySecondPixelOfARowScaled)
{
    present(0x30);
    ASSERT_TRUE(epuck_camera_init(&camera, board.get()));
    std::array<int16_t, 60> r{}, g{}, b{};
    ASSERT_TRUE(epuck_camera_capture(&camera, 50, r.data(), g.data(), b.data()));
    ASSERT_EQ(world.camera_rows_read.size(), 1u);
    uint16_t row = world.camera_rows_read[0];
    EXPECT_EQ(row, 60); // the middle of 120 rows
    for (unsigned i = 0; i < 60; i++) {
        Rgb c = pixel_colour(row, 2 * i);
        EXPECT_EQ(r[i], int(c.r * 3)) << i;
        EXPECT_EQ(g[i], int(c.g * 3 / 2)) << i;
        EXPECT_EQ(b[i], int(c.b * 3)) << i;
        EXPECT_LE(r[i], 93);
        EXPECT_LE(g[i], 94);
    }
    // The top and bottom of the image.
    host_board_advance(board.get(), uint64_t(FCY));
    ASSERT_TRUE(epuck_camera_capture(&camera, 0, r.data(), g.data(), b.data()));
    host_board_advance(board.get(), uint64_t(FCY));
    ASSERT_TRUE(epuck_camera_capture(&camera, 99, r.data(), g.data(), b.data()));
    ASSERT_EQ(world.camera_rows_read.size(), 3u);
    EXPECT_EQ(world.camera_rows_read[1], 0);
    EXPECT_EQ(world.camera_rows_read[2], 118);
}

} // namespace
} // namespace drivers_test
