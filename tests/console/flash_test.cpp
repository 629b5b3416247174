// `aseba flash` end to end: a group of robots of epuck-emu flashed in one
// command through their bootloaders, checked against the image the test
// builds: the command's report, the robots answering again, and, read back
// from the memories epuck-emu saves, every instruction in every robot's
// flash.

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "console_support.hpp"
#include "tools/client/flasher.hpp"
#include "tools/flash/hex_image.hpp"

extern "C" {
#include "bootloader/boot_application.h"
#include "boards/epuck_host/host_board.h"
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

    // Checks that robot `id`'s flash, as epuck-emu keeps it in `folder`,
    // holds `image`.
    static void expect_flash_holds(const std::string &folder,
                                   unsigned id,
                                   const aseba::flash::ProgramImage &image)
    {
        auto board = std::make_unique<hal_board>();
        host_board_init(board.get(), nullptr, nullptr);
        std::string path = folder + "/robot-" + std::to_string(id) + ".mem";
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

    // What the robots wrote is in their files as they wrote it: even a
    // kill -9 loses none of it.
    emulator_.kill_now();
    for (unsigned id = 1; id <= GROUP; id++)
        expect_flash_holds(scratch_.path(), id, image);
}

// The application image that `make dspic30` links for the e-puck, as a
// user flashes it: epuck-image reads it, the robots' bootloaders accept it
// whole (descriptor, CRC), and every instruction of it is in every robot.
TEST_F(Flash, FlashesTheLinkedDspic30Application)
{
    aseba::flash::ProgramImage image =
      aseba::flash::read_microchip_hex_file(DSPIC30_APPLICATION_IMAGE, HAL_FLASH_END);
    ASSERT_NO_THROW(aseba::flash::check_application_image(image));
    size_t pages = aseba::flash::make_pages(image).size();

    CommandResult flash = aseba({ "flash", DSPIC30_APPLICATION_IMAGE });
    EXPECT_EQ(flash.exit_code, 0) << flash.out << flash.err;
    EXPECT_EQ(count_lines_with(
                flash.out, "flashed " + std::to_string(pages) + " pages, running the new image"),
              GROUP)
      << flash.out;
    emulator_.kill_now();
    for (unsigned id = 1; id <= GROUP; id++)
        expect_flash_holds(scratch_.path(), id, image);
}

// A robot flashed with an image its bootloader refuses (here through the
// client library, which `aseba flash` would not do) waits in its bootloader
// and answers no node messages; named by id, it is flashed anyway and comes
// back.
TEST_F(Flash, ARobotWaitingInItsBootloaderIsFlashedByItsId)
{
    aseba::flash::ProgramImage good = test_application(0x11);
    aseba::flash::ProgramImage corrupt = good;
    corrupt.instructions[BOOT_DESCRIPTOR_ADDRESS +
                         BOOT_DESCRIPTOR_CRC_INDEX * PC_UNITS_PER_INSTRUCTION] ^= 1;
    std::string good_file = write_image("good.hex", good);
    {
        aseba::client::Network network;
        network.connect(emulator_.target());
        network.discover();
        std::vector<aseba::client::FlashPage> pages;
        for (const aseba::flash::Page &page : aseba::flash::make_pages(corrupt))
            pages.push_back({ page.number, { page.bytes.begin(), page.bytes.end() } });
        auto outcomes = aseba::client::flash_nodes(
          network, network.select("2"), pages, aseba::client::FlashSettings{}, [](const auto &) {});
        ASSERT_EQ(outcomes.size(), 1u);
        EXPECT_TRUE(outcomes[0].flashed);
        EXPECT_FALSE(outcomes[0].restarted) << "the bootloader accepted a corrupt image";
    }
    CommandResult nodes = aseba({ "nodes" });
    EXPECT_EQ(count_lines_with(nodes.out, "\"e-puck\""), GROUP - 1) << nodes.out;
    EXPECT_FALSE(contains(nodes.out, "node 2 ")) << nodes.out;

    CommandResult repaired = aseba({ "flash", good_file, "--node", "2" });
    EXPECT_EQ(repaired.exit_code, 0) << repaired.out << repaired.err;
    EXPECT_TRUE(contains(repaired.err, "node 2 did not answer as a node")) << repaired.err;
    EXPECT_TRUE(contains(repaired.out, "1 of 1 robots flashed")) << repaired.out;
    nodes = aseba({ "nodes" });
    EXPECT_EQ(count_lines_with(nodes.out, "\"e-puck\""), GROUP) << nodes.out;

    emulator_.stop();
    expect_flash_holds(scratch_.path(), 2, good);
}

// A robot whose flash holds an interrupted flashing (its descriptor erased)
// is in its bootloader from power-on, as the chip's bootloader decides: it
// answers no node messages, waits for an image, and runs once flashed. (It
// started its firmware when epuck-emu started, and showed its bootloader
// only after a reboot.)
TEST(FlashAtPowerOn, ARobotWithAnInterruptedFlashingStartsInItsBootloader)
{
    ScratchFolder scratch;
    auto board = std::make_unique<hal_board>();
    host_board_init(board.get(), nullptr, nullptr); // every flash word erased
    ASSERT_EQ(hal_flash_read(board.get(), BOOT_DESCRIPTOR_ADDRESS), HAL_FLASH_ERASED);
    ASSERT_TRUE(host_board_save_memory(board.get(), (scratch.path() + "/robot-2.mem").c_str()));

    Emulator emulator(2, { "--memory", scratch.path() });
    CommandResult nodes = run_console({ "-t", emulator.target(), "nodes" }, scratch.path());
    EXPECT_EQ(count_lines_with(nodes.out, "\"e-puck\""), 1u) << nodes.out;
    EXPECT_FALSE(contains(nodes.out, "node 2 ")) << nodes.out;

    std::string image =
      scratch.write("good.hex", aseba::flash::write_microchip_hex(test_application(0x22)));
    CommandResult flashed = run_console({ "-t", emulator.target(), "flash", image, "--node", "2" },
                                        scratch.path(),
                                        Milliseconds(30000));
    EXPECT_EQ(flashed.exit_code, 0) << flashed.out << flashed.err;
    EXPECT_TRUE(contains(flashed.out, "1 of 1 robots flashed")) << flashed.out;
    nodes = run_console({ "-t", emulator.target(), "nodes" }, scratch.path());
    EXPECT_EQ(count_lines_with(nodes.out, "\"e-puck\""), 2u) << nodes.out;
}

// An image the robots' bootloaders would refuse takes no robot out of
// service: `aseba flash` checks it whole before it reboots any.
TEST_F(Flash, ImagesTheBootloaderWouldRefuseAreRefusedBeforeAnyRobotIsTouched)
{
    aseba::flash::ProgramImage good = test_application(0x33);
    aseba::flash::ProgramImage bad_data = good;
    bad_data.instructions[APPLICATION_START + 2 * PC_UNITS_PER_INSTRUCTION] ^= 0x100;
    aseba::flash::ProgramImage bare = good;
    bare.instructions.erase(bare.instructions.lower_bound(BOOT_DESCRIPTOR_ADDRESS),
                            bare.instructions.end());
    // Two records for the same instructions: once, the last one won.
    std::string good_text = aseba::flash::write_microchip_hex(good);
    size_t second_record = good_text.find('\n', good_text.find('\n') + 1) + 1;
    std::string overlapping =
      good_text.substr(0, second_record) + good_text.substr(good_text.find('\n') + 1);
    struct Case {
        std::string file;
        std::string complaint;
    };
    const Case cases[] = {
        { write_image("bad-data.hex", bad_data), "the descriptor's CRC is" },
        { write_image("bare.hex", bare), "no application descriptor" },
        { scratch_.write("overlap.hex", overlapping), "records overlap" },
        { scratch_.write("broken.hex", ":020000040000FA\n:0400000000FF\n"), "broken.hex: line 2" },
        { scratch_.path(), "is a folder, not a HEX file" },
    };
    for (const Case &bad : cases) {
        CommandResult flash = aseba({ "flash", bad.file });
        EXPECT_EQ(flash.exit_code, 2) << bad.file;
        EXPECT_TRUE(contains(flash.err, bad.complaint)) << flash.err;
        EXPECT_TRUE(contains(flash.err, "no robot was touched")) << flash.err;
        EXPECT_FALSE(contains(flash.out, "flashing")) << flash.out;
    }
    CommandResult nodes = aseba({ "nodes" });
    EXPECT_EQ(count_lines_with(nodes.out, "running"), GROUP) << nodes.out;
}

// --memory: what a robot stores (its program, its flash) outlives the
// emulator, as it outlives a power cycle on the chip, even when the
// emulator is killed (it writes the file as the robot writes its memories).
class RobotMemory : public testing::TestWithParam<bool>
{
};

TEST_P(RobotMemory, AStoredProgramRunsAgainInTheNextRun)
{
    const bool killed = GetParam();
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
        if (killed)
            emulator.kill_now();
        else
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

std::string stopped_or_killed(const testing::TestParamInfo<bool> &parameter)
{
    return parameter.param ? "Killed" : "Stopped";
}

INSTANTIATE_TEST_SUITE_P(StoppedOrKilled, RobotMemory, testing::Bool(), stopped_or_killed);

} // namespace
