// `aseba flash` end to end: a group of robots of epuck-emu flashed in one
// command through their bootloaders, checked against the image the test
// builds: the command's report, the robots answering again, and, read back
// from the memories epuck-emu saves, every instruction in every robot's
// flash.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "console_support.hpp"
#include "tools/flash/hex_image.hpp"

extern "C" {
#include "bootloader/boot_application.h"
#include "hal/host/host_board.h"
}

using namespace console_test;

namespace
{

constexpr unsigned GROUP = 6;
constexpr uint32_t APPLICATION_START = BOOT_APPLICATION_START; // the bootloader's first page
constexpr uint32_t CODE_INSTRUCTIONS = 700;                    // 22 pages of code
constexpr uint32_t PC_UNITS_PER_INSTRUCTION = 2;

bool contains(const std::string &text, const std::string &part)
{
    return text.find(part) != std::string::npos;
}

// An application the bootloader accepts: distinct 24-bit values in
// [APPLICATION_START, +CODE_INSTRUCTIONS), then the descriptor.
aseba::flash::ProgramImage test_application(uint32_t salt)
{
    aseba::flash::ProgramImage image;
    for (uint32_t i = 0; i < CODE_INSTRUCTIONS; i++)
        image.instructions[APPLICATION_START + i * PC_UNITS_PER_INSTRUCTION] =
          (i * 0x010203u + salt) & 0xFFFFFFu;
    aseba::flash::add_application_descriptor(image, APPLICATION_START);
    return image;
}

size_t count_lines_with(const std::string &text, const std::string &part)
{
    size_t count = 0;
    for (const std::string &line : lines_of(text))
        count += contains(line, part) ? 1 : 0;
    return count;
}

class Flash : public testing::Test
{
  protected:
    Flash()
      : emulator_(GROUP, { "--memory", scratch_.path() })
    {
    }

    CommandResult aseba(std::vector<std::string> arguments)
    {
        arguments.insert(arguments.begin(), { "-t", emulator_.target() });
        return run_console(arguments, scratch_.path(), Milliseconds(30000));
    }

    std::string write_image(const std::string &name, const aseba::flash::ProgramImage &image)
    {
        return scratch_.write(name, aseba::flash::write_microchip_hex(image));
    }

    // Stops epuck-emu and checks that robot `id`'s flash holds `image`.
    void expect_flash_holds(unsigned id, const aseba::flash::ProgramImage &image)
    {
        auto board = std::make_unique<hal_board>();
        host_board_init(board.get(), nullptr, nullptr);
        std::string path = scratch_.path() + "/robot-" + std::to_string(id) + ".mem";
        ASSERT_TRUE(host_board_load_memory(board.get(), path.c_str())) << path;
        size_t wrong = 0;
        for (auto [address, value] : image.instructions)
            wrong += hal_flash_read(board.get(), address) != value ? 1 : 0;
        EXPECT_EQ(wrong, 0u) << "robot " << id << ": instructions that differ from the image";
    }

    ScratchFolder scratch_;
    Emulator emulator_;
};

TEST_F(Flash, FlashesAGroupOfSixInOneCommand)
{
    aseba::flash::ProgramImage image = test_application(0x5A);
    std::string file = write_image("application.hex", image);
    size_t pages = aseba::flash::make_pages(image).size();

    CommandResult flash = aseba({ "flash", file });
    EXPECT_EQ(flash.exit_code, 0) << flash.out << flash.err;
    EXPECT_TRUE(contains(
      flash.out, std::to_string(GROUP) + " of " + std::to_string(GROUP) + " robots flashed"))
      << flash.out;
    EXPECT_EQ(count_lines_with(
                flash.out, "flashed " + std::to_string(pages) + " pages, running the new image"),
              GROUP)
      << flash.out;

    // Every robot answers as a node again.
    CommandResult nodes = aseba({ "nodes" });
    EXPECT_EQ(nodes.exit_code, 0) << nodes.err;
    EXPECT_EQ(count_lines_with(nodes.out, "\"e-puck\""), GROUP) << nodes.out;

    emulator_.stop();
    for (unsigned id = 1; id <= GROUP; id++)
        expect_flash_holds(id, image);
}

TEST_F(Flash, ARefusedImageLeavesTheRobotInItsBootloaderUntilAGoodOne)
{
    aseba::flash::ProgramImage good = test_application(0x11);
    aseba::flash::ProgramImage corrupt = good;
    corrupt.instructions[BOOT_DESCRIPTOR_ADDRESS +
                         BOOT_DESCRIPTOR_CRC_INDEX * PC_UNITS_PER_INSTRUCTION] ^= 1;
    std::string good_file = write_image("good.hex", good);
    std::string corrupt_file = write_image("corrupt.hex", corrupt);

    CommandResult refused = aseba({ "flash", corrupt_file, "--node", "2" });
    EXPECT_EQ(refused.exit_code, 1) << refused.out << refused.err;
    EXPECT_TRUE(contains(refused.out, "FAILED")) << refused.out;
    EXPECT_TRUE(contains(refused.out, "did not accept the image")) << refused.out;
    EXPECT_TRUE(contains(refused.out, "0 of 1 robots flashed")) << refused.out;

    // Robot 2 waits in its bootloader: it is no node; the others still are.
    CommandResult nodes = aseba({ "nodes" });
    EXPECT_EQ(count_lines_with(nodes.out, "\"e-puck\""), GROUP - 1) << nodes.out;
    EXPECT_FALSE(contains(nodes.out, "node 2 ")) << nodes.out;

    // Named by id, it is flashed anyway, and comes back.
    CommandResult repaired = aseba({ "flash", good_file, "--node", "2" });
    EXPECT_EQ(repaired.exit_code, 0) << repaired.out << repaired.err;
    EXPECT_TRUE(contains(repaired.err, "node 2 did not answer as a node")) << repaired.err;
    EXPECT_TRUE(contains(repaired.out, "1 of 1 robots flashed")) << repaired.out;
    nodes = aseba({ "nodes" });
    EXPECT_EQ(count_lines_with(nodes.out, "\"e-puck\""), GROUP) << nodes.out;

    emulator_.stop();
    expect_flash_holds(2, good);
}

TEST_F(Flash, AnImageWithoutDescriptorIsRefusedBeforeAnyRobotIsTouched)
{
    aseba::flash::ProgramImage image = test_application(0x22);
    image.instructions.erase(image.instructions.lower_bound(BOOT_DESCRIPTOR_ADDRESS),
                             image.instructions.end());
    std::string file = write_image("bare.hex", image);

    CommandResult flash = aseba({ "flash", file });
    EXPECT_EQ(flash.exit_code, 1);
    EXPECT_TRUE(contains(flash.err, "no application descriptor")) << flash.err;
    EXPECT_FALSE(contains(flash.out, "flashing")) << flash.out;
    CommandResult nodes = aseba({ "nodes" });
    EXPECT_EQ(count_lines_with(nodes.out, "running"), GROUP) << nodes.out;
}

TEST_F(Flash, ACorruptHexFileIsNamedWithItsLine)
{
    std::string file = scratch_.write("broken.hex", ":020000040000FA\n:0400000000FF\n");
    CommandResult flash = aseba({ "flash", file });
    EXPECT_EQ(flash.exit_code, 1);
    EXPECT_TRUE(contains(flash.err, "broken.hex: line 2")) << flash.err;
}

// --memory: what a robot stores (its program, its flash) outlives the
// emulator, as it outlives a power cycle on the chip.
TEST(RobotMemory, AStoredProgramRunsAgainInTheNextRun)
{
    ScratchFolder scratch;
    std::string program = scratch.write("steady.aseba", "leftSpeed = 321\nrightSpeed = -45\n");
    {
        Emulator emulator(2, { "--memory", scratch.path() });
        CommandResult save =
          run_console({ "-t", emulator.target(), "save", program, "--node", "2" }, scratch.path());
        ASSERT_EQ(save.exit_code, 0) << save.out << save.err;
        // An answer from robot 2 shows that it has handled WRITE_BYTECODE,
        // which came before on its link.
        CommandResult answer = run_console(
          { "-t", emulator.target(), "vars", "leftSpeed", "--node", "2" }, scratch.path());
        ASSERT_EQ(answer.exit_code, 0) << answer.err;
        emulator.stop();
    }
    Emulator emulator(2, { "--memory", scratch.path() });
    CommandResult speeds =
      run_console({ "-t", emulator.target(), "vars", "leftSpeed", "rightSpeed" }, scratch.path());
    EXPECT_EQ(speeds.exit_code, 0) << speeds.err;
    // Robot 2 starts its stored program at boot; robot 1 stored nothing.
    std::vector<std::string> lines = lines_of(speeds.out);
    EXPECT_NE(std::find(lines.begin(), lines.end(), "e-puck 2: leftSpeed = 321"), lines.end())
      << speeds.out;
    EXPECT_NE(std::find(lines.begin(), lines.end(), "e-puck 2: rightSpeed = -45"), lines.end())
      << speeds.out;
    EXPECT_NE(std::find(lines.begin(), lines.end(), "e-puck 1: leftSpeed = 0"), lines.end())
      << speeds.out;
}

} // namespace
