// The e-puck's two images (tools/flash/epuck_image.hpp): the checks of the
// bootloader image and its merge with the application. The expected
// vectors follow the fact sheet (§1.1, §1.7: IVT entry k at PC 0x04 + 2k)
// and bootloader/README.md's layout (the application's table at 0x100, slot
// 1 + k for vector k, 4 PC units per slot; the bootloader at 0x016F00).

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tests/bootloader/test_images.hpp"
#include "tools/flash/epuck_image.hpp"
#include "tools/flash/tiny_bootloader.hpp"

namespace
{

using aseba::flash::HexError;
using aseba::flash::ProgramImage;

using bootloader_test::application_image;
using bootloader_test::bootloader_base;
using bootloader_test::bootloader_image;
using bootloader_test::bootloader_reset;

void expect_refused(const ProgramImage &image, const std::string &message)
{
    try {
        aseba::flash::check_bootloader_image(image);
        FAIL() << "accepted";
    } catch (const HexError &error) {
        EXPECT_NE(std::string(error.what()).find(message), std::string::npos) << error.what();
    }
}

TEST(EpuckImage, ABootloaderImageAsTheLinkerScriptLaysItOutIsAccepted)
{
    EXPECT_NO_THROW(aseba::flash::check_bootloader_image(bootloader_image()));
}

TEST(EpuckImage, ABootloaderImageOutsideItsRegionsIsRefused)
{
    ProgramImage in_store = bootloader_image();
    in_store.instructions[0x016380] = 0;
    expect_refused(in_store, "PC address 0x16380 is outside rows 0-3 and the bootloader region");
    ProgramImage in_application = bootloader_image();
    in_application.instructions[0x100] = 0;
    expect_refused(in_application, "PC address 0x100 is outside");
    ProgramImage in_tiny = bootloader_image();
    in_tiny.instructions[0x017F00] = 0;
    expect_refused(in_tiny, "PC address 0x17F00 is outside");
}

TEST(EpuckImage, ABootloaderImageMustLeadToItselfAndToTheApplicationsSlots)
{
    ProgramImage elsewhere = bootloader_image();
    elsewhere.instructions[0x0] = 0x040200; // GOTO 0x000200
    elsewhere.instructions[0x2] = 0;
    expect_refused(elsewhere, "the reset vector is no GOTO into the bootloader region");
    ProgramImage vector = bootloader_image();
    vector.instructions[0x04 + 2 * 11] = 0x100 + 4 * 11; // T1 at slot 11, not 12
    expect_refused(vector,
                   "IVT entry 11 at 0x1A does not lead to the application's table slot 0x130");
    ProgramImage missing = bootloader_image();
    missing.instructions.erase(0x04 + 2 * 61);
    expect_refused(missing, "IVT entry 61");
}

TEST(EpuckImage, TheFactoryImageHoldsBothAndInstallsThroughTheTinyBootloader)
{
    ProgramImage application = application_image();
    ProgramImage factory = aseba::flash::merge_images(bootloader_image(), application);
    EXPECT_EQ(factory.instructions.size(),
              bootloader_image().instructions.size() + application.instructions.size());
    EXPECT_EQ(factory.instructions.at(0x0), 0x046F40u);
    EXPECT_EQ(factory.instructions.at(0x100), 0x040200u);
    EXPECT_EQ(factory.instructions.at(0x16340), 0xA5EB01u); // the descriptor's magic
    EXPECT_EQ(factory.configuration.at(0xF80000), 0xC706u);
    // Through the factory Tiny Bootloader (§4.3): row 0 leads to Tiny, whose
    // trampoline at 0x017F38 leads to our bootloader's start-up, 0x016F40.
    auto packets = aseba::flash::tiny_bootloader_packets(factory, 7);
    const auto &row_0 = packets.front();
    EXPECT_EQ(row_0[4], 0x40);
    EXPECT_EQ(row_0[5], 0x7F);
    EXPECT_EQ(row_0[6], 0x04);
    const auto &trampoline = packets.back();
    EXPECT_EQ(trampoline[0] | trampoline[1] << 8 | trampoline[2] << 16, 0x017F00);
    std::size_t at = 4 + 3 * ((0x017F38 - 0x017F00) / 2);
    EXPECT_EQ(trampoline[at] | trampoline[at + 1] << 8 | trampoline[at + 2] << 16, 0x046F40);
    EXPECT_EQ(trampoline[at + 3] | trampoline[at + 4] << 8 | trampoline[at + 5] << 16, 0x000001);
    // Every row up to the bootloader's last one, then the trampoline.
    EXPECT_EQ(packets.size(), (bootloader_base + 0x200) / 0x40 + 1);
}

TEST(EpuckImage, OverlappingImagesAreNotMerged)
{
    ProgramImage application = application_image();
    ProgramImage overlapping = bootloader_image();
    overlapping.instructions[0x100] = 0x040200;
    EXPECT_THROW(aseba::flash::merge_images(overlapping, application), HexError);
    ProgramImage other_configuration = bootloader_image();
    application.configuration[0xF80000] = 0xC707;
    EXPECT_THROW(aseba::flash::merge_images(other_configuration, application), HexError);
    application.configuration[0xF80000] = 0xC706; // the same value is fine
    EXPECT_NO_THROW(aseba::flash::merge_images(other_configuration, application));
}

} // namespace
