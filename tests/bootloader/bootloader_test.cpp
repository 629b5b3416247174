// The serial bootloader's core (bootloader/bootloader.h) on a host board:
// a test host speaks the Aseba bootloader messages of protocol.md §6.9,
// flashes an image read from a HEX file, reads it back, resets into it, and
// loses power at every row operation of a flashing. The expected layout is
// the one bootloader/README.md's table gives: the application's pages are
// rows 4 .. (0x16380 / 0x40) - 1; rows 0-3 hold the bootloader image's reset
// GOTO and vector tables and are never written.

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

#include "tools/flash/hex_image.hpp"

extern "C" {
#include "bootloader/bootloader.h"
#include "boards/epuck_host/host_board.h"
}

namespace
{

constexpr uint16_t node_id = 3;
constexpr uint16_t host_id = 0;
// The factory chain (fact sheet §4.3): reset vector = GOTO 0x017F40.
constexpr uint32_t reset_goto_low = 0x047F40;
constexpr uint32_t reset_goto_high = 0x000001;
constexpr uint32_t vector_rows_words = 4 * 32; // rows 0-3
constexpr uint32_t application_end = 0x16380;  // the bytecode store's first row
constexpr uint16_t first_page = 0x100 / 0x40;
constexpr uint16_t page_count = (application_end - 0x100) / 0x40;

// Rows 0-3 as the bootloader image leaves them: the reset GOTO, IVT entry k
// = 0x104 + 4k (the application's table slot 1 + k), AIVT entries pointing
// into the bootloader's code.
uint32_t vector_rows_word(uint32_t index)
{
    if (index == 0)
        return reset_goto_low;
    if (index == 1)
        return reset_goto_high;
    if (index < 2 + 62)
        return 0x104 + 4 * (index - 2);
    if (index >= 0x84 / 2 && index < 0x84 / 2 + 62)
        return 0x16F40 + 2 * (index - 0x84 / 2);
    return 0xFFFFFF;
}

struct Frame {
    uint16_t source;
    uint16_t type;
    std::vector<uint8_t> payload;
    uint16_t word(std::size_t i) const
    {
        return static_cast<uint16_t>(payload[2 * i] | payload[2 * i + 1] << 8);
    }
};

// A board running the bootloader, and what it sent.
struct Robot {
    std::unique_ptr<hal_board> board = std::make_unique<hal_board>();
    bootloader loader{};
    std::vector<uint8_t> sent;
    uint32_t now_ms = 0;

    Robot()
    {
        host_board_init(board.get(), &Robot::collect, this);
        for (uint32_t i = 0; i < vector_rows_words; i++)
            board->flash[i] = vector_rows_word(i);
    }

    static void collect(void *context, const uint8_t *bytes, uint16_t count)
    {
        auto *robot = static_cast<Robot *>(context);
        robot->sent.insert(robot->sent.end(), bytes, bytes + count);
    }

    // Power comes back: a new board with the old memories, bootloader started.
    std::unique_ptr<Robot> reboot() const
    {
        auto robot = std::make_unique<Robot>();
        std::copy(
          std::begin(board->flash), std::end(board->flash), std::begin(robot->board->flash));
        std::copy(
          std::begin(board->eeprom), std::end(board->eeprom), std::begin(robot->board->eeprom));
        robot->start();
        return robot;
    }

    void start()
    {
        boot_start(&loader, board.get(), node_id);
    }

    // Delivers one frame and lets the bootloader handle it.
    boot_status send(uint16_t type, std::vector<uint8_t> payload)
    {
        std::vector<uint8_t> frame{ static_cast<uint8_t>(payload.size()),
                                    static_cast<uint8_t>(payload.size() >> 8),
                                    host_id,
                                    0,
                                    static_cast<uint8_t>(type),
                                    static_cast<uint8_t>(type >> 8) };
        frame.insert(frame.end(), payload.begin(), payload.end());
        EXPECT_TRUE(
          host_board_link_deliver(board.get(), frame.data(), static_cast<uint16_t>(frame.size())));
        return boot_poll(&loader);
    }

    boot_status advance(uint32_t milliseconds)
    {
        now_ms += milliseconds;
        host_board_set_time(board.get(), now_ms);
        return boot_poll(&loader);
    }

    // The frames sent since the last call.
    std::vector<Frame> take_frames()
    {
        std::vector<Frame> frames;
        std::size_t at = 0;
        while (sent.size() - at >= 6) {
            uint16_t length = static_cast<uint16_t>(sent[at] | sent[at + 1] << 8);
            EXPECT_GE(sent.size() - at, 6u + length);
            Frame frame{ static_cast<uint16_t>(sent[at + 2] | sent[at + 3] << 8),
                         static_cast<uint16_t>(sent[at + 4] | sent[at + 5] << 8),
                         std::vector<uint8_t>(sent.begin() + static_cast<long>(at) + 6,
                                              sent.begin() + static_cast<long>(at) + 6 + length) };
            frames.push_back(frame);
            at += 6 + length;
        }
        EXPECT_EQ(at, sent.size());
        sent.clear();
        return frames;
    }
};

std::vector<uint8_t> words(std::initializer_list<uint16_t> values)
{
    std::vector<uint8_t> bytes;
    for (uint16_t v : values) {
        bytes.push_back(static_cast<uint8_t>(v));
        bytes.push_back(static_cast<uint8_t>(v >> 8));
    }
    return bytes;
}

// The only frame sent must be BOOTLOADER_ACK with these payload words.
void expect_ack(Robot &robot, std::vector<uint16_t> expected)
{
    auto frames = robot.take_frames();
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0].source, node_id);
    EXPECT_EQ(frames[0].type, 0x8006); // protocol.md §3
    ASSERT_EQ(frames[0].payload.size(), 2 * expected.size());
    for (std::size_t i = 0; i < expected.size(); i++)
        EXPECT_EQ(frames[0].word(i), expected[i]);
}

std::vector<aseba::flash::Page> pages_of(const std::string &name)
{
    std::ifstream file("tests/bootloader/hex/" + name, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    auto image = aseba::flash::read_microchip_hex(text.str(), application_end - 0x40);
    aseba::flash::add_application_descriptor(image);
    return aseba::flash::make_pages(image);
}

// Writes one page as upstream's BootloaderInterface does; returns whether
// both acks said success.
bool write_page(Robot &robot, const aseba::flash::Page &page)
{
    robot.send(0x8002, words({ node_id, page.number }));
    auto ready = robot.take_frames();
    if (ready.size() != 1 || ready[0].type != 0x8006 || ready[0].word(0) != 0)
        return false;
    for (std::size_t i = 0; i < page.bytes.size(); i += 4) {
        auto chunk = words({ node_id });
        chunk.insert(chunk.end(),
                     page.bytes.begin() + static_cast<long>(i),
                     page.bytes.begin() + static_cast<long>(i) + 4);
        robot.send(0x8003, chunk);
        auto frames = robot.take_frames();
        bool last = i + 4 == page.bytes.size();
        if (!last && !frames.empty())
            return false; // no ack before the page is complete
        if (last && (frames.size() != 1 || frames[0].type != 0x8006 || frames[0].word(0) != 0))
            return false;
    }
    return true;
}

bool flash(Robot &robot, const std::vector<aseba::flash::Page> &pages)
{
    robot.take_frames(); // the description
    for (const auto &page : pages) {
        if (!write_page(robot, page))
            return false;
    }
    return true;
}

// The page as BOOTLOADER_READ_PAGE returns it.
std::vector<uint8_t> read_page(Robot &robot, uint16_t page)
{
    robot.send(0x8001, words({ node_id, page }));
    auto frames = robot.take_frames();
    std::vector<uint8_t> bytes;
    EXPECT_EQ(frames.size(), 33u);
    for (std::size_t i = 0; i + 1 < frames.size(); i++) {
        EXPECT_EQ(frames[i].type, 0x8005);
        EXPECT_EQ(frames[i].payload.size(), 4u);
        bytes.insert(bytes.end(), frames[i].payload.begin(), frames[i].payload.end());
    }
    EXPECT_EQ(frames.back().type, 0x8006);
    EXPECT_EQ(frames.back().payload, words({ 0 }));
    return bytes;
}

void expect_description(Robot &robot)
{
    auto frames = robot.take_frames();
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0].type, 0x8004);
    // 128-byte pages (32 instructions x 4 hex bytes), from row 4 (PC 0x100)
    // up to the bytecode store.
    EXPECT_EQ(frames[0].payload, words({ 128, first_page, page_count }));
}

TEST(Bootloader, SendsItsDescriptionAtStart)
{
    Robot robot;
    robot.start();
    expect_description(robot);
}

TEST(Bootloader, FlashesReadsBackAndStartsTheApplication)
{
    Robot robot;
    robot.start();
    robot.take_frames();
    auto pages = pages_of("application.hex");
    ASSERT_TRUE(flash(robot, pages));
    for (const auto &page : pages) {
        auto bytes = read_page(robot, page.number);
        std::vector<uint8_t> expected(page.bytes.begin(), page.bytes.end());
        EXPECT_EQ(bytes, expected) << "page " << page.number;
    }
    for (uint32_t i = 0; i < vector_rows_words; i++)
        EXPECT_EQ(robot.board->flash[i], vector_rows_word(i)) << "word " << i;
    uint32_t entry = 0;
    ASSERT_TRUE(boot_application_valid(robot.board.get(), &entry));
    EXPECT_EQ(entry, 0x100u); // the reset slot of the application's table
    EXPECT_EQ(robot.send(0x8000, words({ node_id })), BOOT_START_APPLICATION);
    EXPECT_EQ(robot.loader.application_entry, 0x100u);
    expect_ack(robot, { 0 });
}

TEST(Bootloader, StartsAValidApplicationAfterTheTimeout)
{
    Robot first;
    first.start();
    ASSERT_TRUE(flash(first, pages_of("application.hex")));
    auto robot = first.reboot();
    EXPECT_EQ(robot->advance(BOOT_WAIT_MS - 1), BOOT_STAY);
    EXPECT_EQ(robot->advance(1), BOOT_START_APPLICATION);
    EXPECT_EQ(robot->loader.application_entry, 0x100u);
}

TEST(Bootloader, StaysWhenAddressedBeforeTheTimeout)
{
    Robot first;
    first.start();
    ASSERT_TRUE(flash(first, pages_of("application.hex")));
    auto robot = first.reboot();
    robot->take_frames();
    robot->send(0xA00E, words({ node_id })); // REBOOT: a host wants the bootloader
    expect_description(*robot);
    EXPECT_EQ(robot->advance(10 * BOOT_WAIT_MS), BOOT_STAY);
}

TEST(Bootloader, StaysWithoutAValidApplication)
{
    Robot robot;
    robot.start();
    robot.take_frames();
    EXPECT_EQ(robot.advance(10 * BOOT_WAIT_MS), BOOT_STAY);
    EXPECT_EQ(robot.send(0x8000, words({ node_id })), BOOT_STAY);
    auto frames = robot.take_frames();
    ASSERT_EQ(frames.size(), 2u); // the ack, then the description again
    EXPECT_EQ(frames[0].type, 0x8006);
    EXPECT_EQ(frames[1].type, 0x8004);
}

TEST(Bootloader, ADamagedApplicationIsNotStarted)
{
    Robot robot;
    robot.start();
    ASSERT_TRUE(flash(robot, pages_of("application.hex")));
    robot.board->flash[0x200 / 2] ^= 0x10; // one bit of the code
    uint32_t entry = 0;
    EXPECT_FALSE(boot_application_valid(robot.board.get(), &entry));
    robot.board->flash[0x200 / 2] ^= 0x10;
    EXPECT_TRUE(boot_application_valid(robot.board.get(), &entry));
    robot.board->flash[0x100 / 2] ^= 0x01; // the table's reset slot is checked too
    EXPECT_FALSE(boot_application_valid(robot.board.get(), &entry));
    auto rebooted = robot.reboot();
    EXPECT_EQ(rebooted->advance(2 * BOOT_WAIT_MS), BOOT_STAY);
}

TEST(Bootloader, RefusesPagesOutsideTheApplication)
{
    Robot robot;
    robot.start();
    robot.take_frames();
    auto before =
      std::vector<uint32_t>(std::begin(robot.board->flash), std::end(robot.board->flash));
    // Rows 0-3 (reset GOTO, IVT, AIVT), the bytecode store's first page, the
    // Aseba bootloader's first page, the factory bootloader's, beyond flash.
    for (uint16_t page : { uint16_t(0),
                           uint16_t(1),
                           uint16_t(2),
                           uint16_t(3),
                           uint16_t(application_end / 0x40),
                           uint16_t(0x16F00 / 0x40),
                           uint16_t(0x17F00 / 0x40),
                           uint16_t(0xFFFF) }) {
        robot.send(0x8002, words({ node_id, page }));
        expect_ack(robot, { 2, static_cast<uint16_t>(page * 0x40u) });
        robot.send(0x8003, words({ node_id, 0x1111, 0x0011 }));
        expect_ack(robot, { 3 }); // not programming
        robot.send(0x8001, words({ node_id, page }));
        expect_ack(robot, { 2, static_cast<uint16_t>(page * 0x40u) });
    }
    EXPECT_TRUE(std::equal(before.begin(), before.end(), std::begin(robot.board->flash)));
}

TEST(Bootloader, AnswersBadFramesWithTheProtocolCodes)
{
    Robot robot;
    robot.start();
    robot.take_frames();
    robot.send(0x8003, words({ node_id, 1, 2 }));
    expect_ack(robot, { 3 }); // data without WRITE_PAGE
    robot.send(0x8002, words({ node_id, 5, 0 }));
    expect_ack(robot, { 1 }); // WRITE_PAGE with an extra word
    robot.send(0x8002, words({ node_id, 5 }));
    expect_ack(robot, { 0 });
    robot.send(0x8003, words({ node_id, 1 }));
    expect_ack(robot, { 1 }); // a 2-byte chunk
    robot.send(0x8003, words({ node_id, 1, 2 }));
    expect_ack(robot, { 3 }); // the bad chunk ended programming
    robot.send(0x8001, words({ node_id }));
    expect_ack(robot, { 1 }); // READ_PAGE without a page
}

TEST(Bootloader, IgnoresFramesForOtherNodesAndOtherMessages)
{
    Robot robot;
    robot.start();
    robot.take_frames();
    robot.send(0x8002, words({ node_id + 1, 5 }));
    robot.send(0xA000, words({ 5 }));                    // GET_DESCRIPTION broadcast
    robot.send(0x0001, std::vector<uint8_t>(500, 0x80)); // a long user event
    robot.send(0x8002, {});                              // no dest
    EXPECT_TRUE(robot.take_frames().empty());
    // Still in sync: the next frame is understood.
    robot.send(0x8002, words({ node_id, 5 }));
    expect_ack(robot, { 0 });
}

TEST(Bootloader, DropsAFrameCutShortByASilence)
{
    Robot robot;
    robot.start();
    robot.take_frames();
    uint8_t partial[] = { 4, 0, 0, 0, 0x02 };
    ASSERT_TRUE(host_board_link_deliver(robot.board.get(), partial, sizeof partial));
    boot_poll(&robot.loader);
    robot.advance(BOOT_FRAME_GAP_MS + 1);
    robot.send(0x8002, words({ node_id, 5 }));
    expect_ack(robot, { 0 });
}

// Counts the flash operations of flashing `pages` over a valid application.
uint32_t operations_of_flashing(const Robot &start, const std::vector<aseba::flash::Page> &pages)
{
    auto robot = start.reboot();
    uint32_t before = robot->board->memory_operations;
    EXPECT_TRUE(flash(*robot, pages));
    return robot->board->memory_operations - before;
}

// How many pages differ from what the robot's flash holds.
std::size_t changed_pages(const Robot &robot, const std::vector<aseba::flash::Page> &pages)
{
    std::size_t changed = 0;
    for (const auto &page : pages) {
        for (std::size_t i = 0; i < 32; i++) {
            uint32_t wanted =
              page.bytes[4 * i] | page.bytes[4 * i + 1] << 8 | page.bytes[4 * i + 2] << 16;
            if (robot.board->flash[page.number * 0x20 + i] != wanted) {
                changed++;
                break;
            }
        }
    }
    return changed;
}

TEST(Bootloader, ReflashingTheSameImageRewritesOnlyTheDescriptor)
{
    Robot first;
    first.start();
    auto pages = pages_of("application.hex");
    ASSERT_TRUE(flash(first, pages));
    auto robot = first.reboot();
    uint32_t before = robot->board->memory_operations;
    ASSERT_TRUE(flash(*robot, pages));
    // Only the descriptor: erased when the first page comes, then its own
    // page's erase and write.
    EXPECT_EQ(robot->board->memory_operations - before, 3u);
    uint32_t entry = 0;
    EXPECT_TRUE(boot_application_valid(robot->board.get(), &entry));
}

TEST(Bootloader, APowerCutAtAnyRowOperationLeavesTheBootloaderInCharge)
{
    // An old application (another table and code) is on the robot.
    auto new_pages = pages_of("application.hex");
    Robot start;
    start.start();
    {
        aseba::flash::ProgramImage image;
        image.instructions = { { 0x100, 0x040300 },
                               { 0x102, 0 },
                               { 0x104, 0x040302 },
                               { 0x106, 0 },
                               { 0x300, 0xAABBCC } };
        aseba::flash::add_application_descriptor(image);
        ASSERT_TRUE(flash(start, aseba::flash::make_pages(image)));
    }
    uint32_t old_entry = 0;
    ASSERT_TRUE(boot_application_valid(start.board.get(), &old_entry));
    const uint32_t descriptor_end_word = (application_end - 0x40 + 4) / 2;
    ASSERT_EQ(start.board->flash[descriptor_end_word], 0x302u);

    uint32_t operations = operations_of_flashing(start, new_pages);
    // The descriptor's erase, then an erase and a write per page that
    // changes (the table's row among them: its vectors differ).
    EXPECT_EQ(operations, 1 + 2 * changed_pages(start, new_pages));
    EXPECT_GE(changed_pages(start, new_pages), 3u);
    for (uint32_t cut = 1; cut <= operations; cut++) {
        auto robot = start.reboot();
        host_board_cut_power_at(robot->board.get(), cut);
        flash(*robot, new_pages);
        robot->board->powered_off = false;
        auto rebooted = robot->reboot();
        uint32_t entry = 0;
        bool valid = boot_application_valid(rebooted->board.get(), &entry);
        boot_status status = rebooted->advance(2 * BOOT_WAIT_MS);
        if (cut < operations) {
            EXPECT_FALSE(valid) << "cut at " << cut;
            EXPECT_EQ(status, BOOT_STAY) << "cut at " << cut;
        } else if (valid) { // the cut tore the descriptor's row after its first words
            EXPECT_EQ(rebooted->board->flash[descriptor_end_word], 0x5C2u);
        }
        // No cut reaches rows 0-3: the reset GOTO and both vector tables
        // still lead to the bootloader and the application's table.
        for (uint32_t i = 0; i < vector_rows_words; i++)
            ASSERT_EQ(rebooted->board->flash[i], vector_rows_word(i))
              << "cut at " << cut << ", word " << i;
        // Flashing again after the reboot succeeds.
        auto again = robot->reboot();
        again->take_frames();
        ASSERT_TRUE(flash(*again, new_pages)) << "cut at " << cut;
        EXPECT_EQ(again->send(0x8000, words({ node_id })), BOOT_START_APPLICATION);
        ASSERT_TRUE(boot_application_valid(again->board.get(), &entry));
        EXPECT_EQ(entry, 0x100u);
        EXPECT_EQ(again->board->flash[descriptor_end_word], 0x5C2u);
    }
}

// Writes `image`'s pages straight into the robot's flash.
void install(Robot &robot, const aseba::flash::ProgramImage &image)
{
    for (const auto &page : aseba::flash::make_pages(image)) {
        for (uint32_t i = 0; i < 32; i++)
            robot.board->flash[page.number * 32u + i] =
              page.bytes[4 * i] | page.bytes[4 * i + 1] << 8 | page.bytes[4 * i + 2] << 16;
    }
}

TEST(Bootloader, AcceptsOnlyEntriesThatASixteenBitJumpReaches)
{
    // An application reaching past PC 0x10000: its descriptor is valid with
    // the entry 0x100 and refused when the entry is changed (the entry is
    // not under the CRC) to 0x10000, to 0xFE (below the application) or to
    // an odd address.
    aseba::flash::ProgramImage image;
    image.instructions = { { 0x100, 0x040200 }, { 0x102, 0 }, { 0x10002, 0x123456 } };
    aseba::flash::add_application_descriptor(image);
    Robot robot;
    install(robot, image);
    uint32_t entry = 0;
    ASSERT_TRUE(boot_application_valid(robot.board.get(), &entry));
    EXPECT_EQ(entry, 0x100u);
    const uint32_t entry_word = (application_end - 0x40 + 2) / 2;
    for (uint32_t bad : { 0x10000u, 0xFEu, 0x201u }) {
        robot.board->flash[entry_word] = bad;
        EXPECT_FALSE(boot_application_valid(robot.board.get(), &entry)) << bad;
    }
    robot.board->flash[entry_word] = 0xFFFE;
    EXPECT_TRUE(boot_application_valid(robot.board.get(), &entry));
    EXPECT_EQ(entry, 0xFFFEu);
}

} // namespace
