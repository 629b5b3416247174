// The first installation through the factory Tiny Bootloader, end to end:
// the real uploader (`epuck-image install`, tools/flash/install_command.hpp,
// serial link included) talks over a pseudo-terminal to a Tiny Bootloader
// simulated from the fact sheet (tiny_simulator.hpp) on a host board's
// flash. The expectations come from the fact sheet (§4.1-4.4: the reset
// vector's bytes, the trampoline row, rows written erase + program, 'N' on a
// bad checksum) and from bootloader/README.md's layout (our bootloader at
// 0x016F00, its start-up at 0x016F40 in these images, the application's
// entry at 0x100).

#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/bootloader/test_images.hpp"
#include "tests/bootloader/tiny_simulator.hpp"
#include "tools/flash/epuck_image.hpp"
#include "tools/flash/install_command.hpp"
#include "tools/flash/tiny_serial_link.hpp"
#include "tools/flash/tiny_upload.hpp"

extern "C" {
#include "bootloader/boot_application.h"
#include "bootloader/bootloader.h"
}

namespace
{

using aseba::flash::ProgramImage;
using aseba::test::TinySimulator;
using std::chrono::milliseconds;

using bootloader_test::bootloader_base;
using bootloader_test::bootloader_code_end;
using bootloader_test::bootloader_image;
using bootloader_test::bootloader_reset;
constexpr uint32_t application_entry = 0x100; // bootloader/README.md: slot 0 of its table
constexpr uint32_t erased = 0xFFFFFF;
constexpr uint32_t row_span = 0x40;
constexpr uint16_t robot_number = 7;
constexpr uint16_t factory_robot_number = 1234;
// Rows 0 up to the one holding the image's last instruction, then Tiny's
// trampoline row (fact sheet §4.3).
constexpr std::size_t rows_sent = (bootloader_code_end - 2) / row_span + 1 + 1;

ProgramImage factory_image()
{
    return aseba::flash::merge_images(bootloader_image(), bootloader_test::application_image());
}

// The factory image as a HEX file in a temporary folder, removed at the end.
struct FactoryFile {
    std::string path;
    FactoryFile()
    {
        std::string pattern = (std::filesystem::temp_directory_path() / "tiny_upload_test.XXXXXX");
        std::vector<char> folder(pattern.begin(), pattern.end());
        folder.push_back('\0');
        EXPECT_NE(mkdtemp(folder.data()), nullptr);
        path = std::string(folder.data()) + "/epuck-aseba-factory.hex";
        std::ofstream(path, std::ios::binary) << aseba::flash::write_microchip_hex(factory_image());
    }
    ~FactoryFile()
    {
        std::remove(path.c_str());
        rmdir(path.substr(0, path.rfind('/')).c_str());
    }
};

struct CommandResult {
    int status;
    std::string out;
    std::string err;
};

CommandResult install(const std::vector<std::string> &arguments)
{
    std::ostringstream out, err;
    int status = aseba::flash::run_install_command(arguments, out, err);
    return { status, out.str(), err.str() };
}

bool contains(const std::string &text, const std::string &part)
{
    return text.find(part) != std::string::npos;
}

uint32_t flash(const hal_board &board, uint32_t pc)
{
    return board.flash[pc / 2];
}

// The image's instructions that differ in flash (but the reset vector), as
// "PC: flash != image" lines, the first few.
std::string image_differences(const hal_board &board, const ProgramImage &image)
{
    constexpr std::size_t differences_shown = 5;
    std::string differences;
    std::size_t count = 0;
    for (const auto &[pc, value] : image.instructions) {
        if (pc < 4 || flash(board, pc) == value)
            continue;
        if (++count <= differences_shown)
            differences += std::to_string(pc) + ": " + std::to_string(flash(board, pc)) +
                           " != " + std::to_string(value) + "\n";
    }
    return count == 0 ? "" : std::to_string(count) + " differ:\n" + differences;
}

// Everything the fact sheet says an installation of `image` leaves, and
// that the reset then leads through Tiny to our bootloader, whose core
// starts the application.
void expect_installed(hal_board &board, const ProgramImage &image, uint16_t number)
{
    EXPECT_EQ(image_differences(board, image), "");
    // The reset vector still leads to Tiny: bytes 40 7F 04 00 01 00 00 00.
    EXPECT_EQ(flash(board, 0x0), 0x047F40u);
    EXPECT_EQ(flash(board, 0x2), 0x000001u);
    // Rows up to the image's last are written, missing instructions erased
    // (the bytecode store's rows among them); the rows above are untouched.
    std::size_t padded_wrong = 0, beyond_wrong = 0;
    for (uint32_t pc = 4; pc < aseba::test::tiny_base; pc += 2) {
        if (pc < (rows_sent - 1) * row_span) {
            if (!image.instructions.contains(pc) && flash(board, pc) != erased)
                padded_wrong++;
        } else if (flash(board, pc) != aseba::test::old_program_word(pc)) {
            beyond_wrong++;
        }
    }
    EXPECT_EQ(padded_wrong, 0u);
    EXPECT_EQ(beyond_wrong, 0u);
    // Tiny's first row: erased but the robot number and GOTO 0x016F40 (0x046F40, 0x000001).
    for (uint32_t pc = aseba::test::tiny_base; pc < aseba::test::tiny_entry; pc += 2) {
        uint32_t expected = pc == 0x017F36   ? number
                            : pc == 0x017F38 ? 0x046F40
                            : pc == 0x017F3A ? 0x000001
                                             : erased;
        EXPECT_EQ(flash(board, pc), expected) << "PC " << pc;
    }
    // Tiny's code is untouched.
    for (uint32_t pc = aseba::test::tiny_entry; pc < 0x017FF4; pc += 2)
        ASSERT_EQ(flash(board, pc), aseba::test::tiny_code_word(pc)) << "PC " << pc;
    EXPECT_EQ(flash(board, 0x017FF8), aseba::test::reset_opcode);

    aseba::test::ResetPath path = aseba::test::follow_reset(&board);
    EXPECT_TRUE(path.enters_tiny);
    EXPECT_FALSE(path.stays_in_tiny);
    EXPECT_EQ(path.runs_at, bootloader_reset);

    uint32_t entry = 0;
    EXPECT_TRUE(boot_application_valid(&board, &entry));
    EXPECT_EQ(entry, application_entry);
    // Our bootloader's core, not addressed by a host, starts it after its second.
    bootloader loader{};
    boot_start(&loader, &board, 1); // at time 0: the simulator never moves the board's clock
    host_board_set_time(&board, BOOT_WAIT_MS + 1);
    EXPECT_EQ(boot_poll(&loader), BOOT_START_APPLICATION);
    EXPECT_EQ(loader.application_entry, application_entry);
}

TEST(TinyUpload, TheFactoryImageInstallsThroughTinyAndResetsIntoOurBootloaderThenTheApplication)
{
    FactoryFile file;
    TinySimulator robot(factory_robot_number);
    robot.start(milliseconds(100)); // the user presses reset after 0.1 s
    CommandResult result = install(
      { "--port", robot.device(), "--id", std::to_string(robot_number), "--wait", "5", file.path });
    robot.stop();
    EXPECT_EQ(result.status, 0) << result.err;
    EXPECT_EQ(result.err, "");
    EXPECT_TRUE(contains(result.out, "press the robot's reset button")) << result.out;
    EXPECT_TRUE(
      contains(result.out, "rows " + std::to_string(rows_sent) + "/" + std::to_string(rows_sent)))
      << result.out;
    EXPECT_TRUE(contains(result.out, "GOTO 0x016F40")) << result.out;

    const TinySimulator::Record &record = robot.record();
    EXPECT_EQ(record.resets, 1u);
    EXPECT_EQ(record.hellos_answered, 1u);
    EXPECT_EQ(record.packets, rows_sent);
    EXPECT_EQ(record.rows_written, rows_sent);
    EXPECT_EQ(record.bad_checksums, 0u);
    EXPECT_TRUE(record.ended);
    EXPECT_EQ(record.led_ticks, 0x95); // about 2 s, as epuckuploadbt (§4.2)
    expect_installed(robot.board(), factory_image(), robot_number);
}

TEST(TinyUpload, ARowAnsweredNIsSentAgainAndTheInstallationSucceeds)
{
    FactoryFile file;
    TinySimulator robot;
    robot.corrupt_packet(3); // row 2 (PC 0x80) arrives with a corrupted byte once
    robot.start(milliseconds(0));
    CommandResult result = install({ "--port", robot.device(), "--wait", "5", file.path });
    robot.stop();
    EXPECT_EQ(result.status, 0) << result.err;
    EXPECT_TRUE(contains(result.out, "Row 3 (PC 0x000080) had a bad checksum ('N')")) << result.out;
    EXPECT_TRUE(contains(result.out, "1 sent again")) << result.out;
    EXPECT_EQ(robot.record().bad_checksums, 1u);
    EXPECT_EQ(robot.record().packets, rows_sent + 1);
    EXPECT_EQ(robot.record().rows_written, rows_sent);
    expect_installed(robot.board(), factory_image(), 0);
}

TEST(TinyUpload, WithoutAnAnswerTheCommandGivesUpAfterItsWait)
{
    FactoryFile file;
    TinySimulator robot(factory_robot_number);
    robot.start(std::nullopt); // nobody presses reset
    auto started = std::chrono::steady_clock::now();
    CommandResult result = install({ "--port", robot.device(), "--wait", "0.3", file.path });
    auto took = std::chrono::steady_clock::now() - started;
    robot.stop();
    EXPECT_EQ(result.status, 1);
    EXPECT_TRUE(contains(result.err,
                         "no answer from the Tiny Bootloader within 0.3 s: press the "
                         "robot's reset button"))
      << result.err;
    EXPECT_GE(took, milliseconds(300));
    EXPECT_LT(took, milliseconds(2000));
    EXPECT_EQ(robot.record().packets, 0u);
    auto factory = std::make_unique<hal_board>();
    aseba::test::put_factory_flash(factory.get(), factory_robot_number);
    EXPECT_TRUE(std::equal(
      std::begin(factory->flash), std::end(factory->flash), std::begin(robot.board().flash)));
}

TEST(TinyUpload, UsageErrorsAndHelp)
{
    CommandResult help = install({ "--help" });
    EXPECT_EQ(help.status, 0);
    EXPECT_TRUE(contains(help.out, "usage: epuck-image install --port DEVICE"));
    EXPECT_EQ(install({ "file.hex" }).status, 2);
    EXPECT_EQ(install({ "--port", "/dev/null" }).status, 2);
    EXPECT_EQ(install({ "--port", "/dev/null", "--id", "65536", "f.hex" }).status, 2);
    EXPECT_EQ(install({ "--port", "/dev/null", "--wait", "0", "f.hex" }).status, 2);
    CommandResult missing = install({ "--port", "/dev/null", "no-such-file.hex" });
    EXPECT_EQ(missing.status, 2); // an input file that cannot be read, as for every tool
    EXPECT_TRUE(contains(missing.err, "no-such-file.hex: cannot be read")) << missing.err;
    FactoryFile file;
    CommandResult not_a_tty = install({ "--port", "/dev/null", file.path });
    EXPECT_EQ(not_a_tty.status, 1);
    EXPECT_TRUE(contains(not_a_tty.err, "not a serial device")) << not_a_tty.err;
}

// Power cuts: the N-th flash operation of the installation (row k's erase
// is operation 2k + 1, its programming 2k + 2) loses power; the uploader
// gets no reply. Then power comes back and the user installs again. The
// fact sheet (§4.3) says the reset vector then leads to Tiny; in this model
// that holds once row 0's erase is over: a cut during that erase leaves
// the first half of row 0 erased (the host board's rule), the reset GOTO
// with it, and no reset reaches Tiny any more.
struct Cut {
    const char *name;
    uint32_t operation;
    bool reset_enters_tiny; // what the fact sheet's model gives after the cut
};

class TinyUploadPowerCut : public testing::TestWithParam<Cut>
{
};

TEST_P(TinyUploadPowerCut, ASecondInstallationSucceedsUnlessTheCutHitRow0sErase)
{
    const Cut &cut = GetParam();
    FactoryFile file;
    TinySimulator robot(factory_robot_number);
    host_board_cut_power_at(&robot.board(), cut.operation);
    robot.start(milliseconds(0));
    {
        auto link = aseba::flash::open_tiny_serial_link(robot.device());
        aseba::flash::TinyUploadSettings settings;
        settings.handshake_timeout = milliseconds(3000);
        // One hello: the simulated robot is in Tiny from the start. A second
        // one, sent while a loaded machine keeps the simulator from
        // answering the first, reaches Tiny as the first byte of row 1, which
        // then gets no reply (as CI once saw) or a bad checksum.
        settings.hello_interval = settings.handshake_timeout;
        // Short, so that the cut is noticed soon, yet long enough for a
        // loaded machine running tests side by side.
        settings.reply_timeout = milliseconds(3000);
        auto packets = aseba::flash::tiny_bootloader_packets(factory_image(), robot_number);
        try {
            aseba::flash::tiny_upload(*link, packets, settings);
            ADD_FAILURE() << "the installation did not notice the power cut";
        } catch (const aseba::flash::TinyUploadError &error) {
            EXPECT_TRUE(contains(
              error.what(), "no reply to row " + std::to_string((cut.operation + 1) / 2) + "/"))
              << error.what();
        }
    }
    robot.stop();
    EXPECT_TRUE(robot.record().powered_off);
    host_board_restore_power(&robot.board());

    aseba::test::ResetPath path = aseba::test::follow_reset(&robot.board());
    EXPECT_EQ(path.enters_tiny, cut.reset_enters_tiny);
    if (cut.reset_enters_tiny) { // the trampoline is the factory's or erased: back into Tiny
        EXPECT_TRUE(path.stays_in_tiny);
    }

    robot.start(milliseconds(0));
    CommandResult again = install({ "--port",
                                    robot.device(),
                                    "--id",
                                    std::to_string(robot_number),
                                    "--wait",
                                    "0.5",
                                    file.path });
    robot.stop();
    if (cut.reset_enters_tiny) {
        EXPECT_EQ(again.status, 0) << again.err;
        expect_installed(robot.board(), factory_image(), robot_number);
    } else { // the reset vector is lost: only a programmer helps
        EXPECT_EQ(again.status, 1);
        EXPECT_TRUE(contains(again.err, "no answer from the Tiny Bootloader")) << again.err;
    }
}

INSTANTIATE_TEST_SUITE_P(Cuts,
                         TinyUploadPowerCut,
                         testing::Values(Cut{ "Row0Erase", 1, false },
                                         Cut{ "Row0Program", 2, true },
                                         Cut{ "Row1Erase", 3, true },
                                         Cut{ "MiddleRowProgram", 2 * 700 + 2, true },
                                         Cut{ "TrampolineErase", 2 * (rows_sent - 1) + 1, true },
                                         Cut{ "TrampolineProgram", 2 * (rows_sent - 1) + 2, true }),
                         [](const testing::TestParamInfo<Cut> &cut) {
                             return std::string(cut.param.name);
                         });

// The protocol without a tty: a link that answers as a script says.
class ScriptedLink : public aseba::flash::TinyLink
{
  public:
    std::deque<uint8_t> replies;
    std::vector<std::vector<uint8_t>> sent;
    void send(std::span<const uint8_t> bytes) override
    {
        sent.emplace_back(bytes.begin(), bytes.end());
    }
    std::optional<uint8_t> receive(milliseconds) override
    {
        if (replies.empty())
            return std::nullopt;
        uint8_t byte = replies.front();
        replies.pop_front();
        return byte;
    }
    void discard_input() override {}
    void finish_sending() override {}
};

TEST(TinyUploadProtocol, ARowRefusedAfterEveryResendStopsTheInstallation)
{
    ScriptedLink link;
    // A 'K' from a running firmware is no answer; then Tiny's 'q' 'K', then 'N' 4 times.
    link.replies = { 'K', 0x71, 'K', 'N', 'N', 'N', 'N' };
    auto packets = aseba::flash::tiny_bootloader_packets(factory_image(), robot_number);
    aseba::flash::TinyUploadSettings settings;
    settings.hello_interval = milliseconds(1);
    settings.handshake_timeout = milliseconds(100);
    try {
        aseba::flash::tiny_upload(link, packets, settings);
        FAIL() << "accepted";
    } catch (const aseba::flash::TinyUploadError &error) {
        EXPECT_TRUE(contains(error.what(),
                             "row 1/" + std::to_string(rows_sent) +
                               " (PC 0x000000) arrived with a bad checksum 4 times"))
          << error.what();
    }
    ASSERT_EQ(link.sent.size(), 1u + 4u); // one 0xC1, then the first packet 4 times
    EXPECT_EQ(link.sent[0], std::vector<uint8_t>{ 0xC1 });
    for (std::size_t i = 1; i < link.sent.size(); i++)
        EXPECT_EQ(link.sent[i], std::vector<uint8_t>(packets[0].begin(), packets[0].end()));
}

TEST(TinyUploadProtocol, AnyOtherReplyStopsTheInstallation)
{
    ScriptedLink link;
    link.replies = { 0x71, 'K', 'K', 'X' };
    auto packets = aseba::flash::tiny_bootloader_packets(factory_image(), robot_number);
    try {
        aseba::flash::tiny_upload(link, packets, {});
        FAIL() << "accepted";
    } catch (const aseba::flash::TinyUploadError &error) {
        EXPECT_TRUE(contains(error.what(), "unexpected reply 0x58 to row 2/")) << error.what();
    }
}

} // namespace
