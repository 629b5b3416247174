// The fail-safe record store (store/bytecode_store.h) on the host
// board: round trips, a power cut at every flash operation of a save, slots
// damaged by flipped bits, and sequence numbers that wrap.

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "tests/bootloader/xmodem.hpp"

extern "C" {
#include "robots/epuck/devices/epuck_selector.h"
#include "store/bytecode_store.h"
#include "robots/epuck/epuck_description.h"
#include "boards/epuck_host/host_board.h"
}

namespace
{

using Words = std::vector<uint16_t>;

std::unique_ptr<hal_board> new_board()
{
    auto board = std::make_unique<hal_board>();
    host_board_init(board.get(), nullptr, nullptr);
    return board;
}

// A reboot: a new board that keeps only what the memories hold.
std::unique_ptr<hal_board> reboot(const hal_board &old)
{
    auto board = new_board();
    std::copy(std::begin(old.eeprom), std::end(old.eeprom), std::begin(board->eeprom));
    std::copy(std::begin(old.flash), std::end(old.flash), std::begin(board->flash));
    return board;
}

Words program(uint16_t count, uint16_t seed)
{
    Words words(count);
    uint32_t state = seed * 2654435761u + 1;
    for (auto &word : words) {
        state = state * 1103515245u + 12345u;
        word = static_cast<uint16_t>(state >> 16);
    }
    return words;
}

std::optional<Words> load_bytecode(hal_board *board)
{
    Words words(FIRMWARE_BYTECODE_WORDS);
    uint16_t count = 0;
    if (!store_load_bytecode(board, words.data(), static_cast<uint16_t>(words.size()), &count))
        return std::nullopt;
    words.resize(count);
    return words;
}

bool save_bytecode(hal_board *board, const Words &words)
{
    return store_save_bytecode(board, words.data(), static_cast<uint16_t>(words.size()));
}

// Writes a slot exactly as bytecode_store.h documents the format, straight
// into the board's flash.
void write_slot(hal_board *board,
                uint32_t slot_address,
                uint16_t magic,
                uint16_t sequence,
                const Words &words)
{
    std::vector<uint8_t> checked;
    auto add = [&](uint16_t value) {
        checked.push_back(static_cast<uint8_t>(value & 0xFF));
        checked.push_back(static_cast<uint8_t>(value >> 8));
    };
    add(magic);
    add(sequence);
    add(static_cast<uint16_t>(words.size()));
    for (uint16_t word : words)
        add(word);
    uint16_t crc = bootloader_test::crc_xmodem(checked);
    std::vector<uint8_t> stream(checked.begin(), checked.begin() + 6);
    stream.push_back(static_cast<uint8_t>(crc & 0xFF));
    stream.push_back(static_cast<uint8_t>(crc >> 8));
    stream.insert(stream.end(), checked.begin() + 6, checked.end());
    while (stream.size() % 3 != 0)
        stream.push_back(0xFF);
    for (size_t i = 0; i < stream.size(); i += 3) {
        uint32_t instruction = stream[i] | (stream[i + 1] << 8) | (stream[i + 2] << 16);
        board->flash[slot_address / 2 + i / 3] = instruction;
    }
}

TEST(Crc, MatchesTheXmodemCheckValue)
{
    // The catalogue check value of CRC-16/XMODEM over "123456789".
    std::vector<uint8_t> text{ '1', '2', '3', '4', '5', '6', '7', '8', '9' };
    EXPECT_EQ(bootloader_test::crc_xmodem(text), 0x31C3);
}

TEST(Layout, FitsTheLinkerRegion)
{
    EXPECT_LE(STORE_ROWS_USED, STORE_REGION_ROWS);
    // 1024 words plus the 8-byte header at 96 bytes a row.
    EXPECT_EQ(STORE_BYTECODE_SLOT_BLOCKS, (1024u * 2 + 8 + 95) / 96);
    store_place place;
    store_bytecode_place(&place);
    EXPECT_GE(store_capacity(&place), 1024u);
    store_settings_place(&place);
    EXPECT_EQ(store_capacity(&place), (96u - 8) / 2);
}

TEST(Store, EmptyFlashHoldsNoProgram)
{
    auto board = new_board();
    EXPECT_FALSE(load_bytecode(board.get()).has_value());
}

TEST(Store, RoundTripsProgramsOfEverySize)
{
    auto board = new_board();
    for (uint16_t count : { 0, 1, 44, 45, 500, 1023, 1024 }) {
        Words words = program(count, count);
        ASSERT_TRUE(save_bytecode(board.get(), words)) << count;
        auto rebooted = reboot(*board);
        EXPECT_EQ(load_bytecode(rebooted.get()), words) << count;
    }
}

TEST(Store, RefusesAProgramLargerThanASlot)
{
    auto board = new_board();
    ASSERT_TRUE(save_bytecode(board.get(), program(10, 1)));
    store_place place;
    store_bytecode_place(&place);
    Words too_long = program(static_cast<uint16_t>(store_capacity(&place) + 1), 2);
    EXPECT_FALSE(save_bytecode(board.get(), too_long));
    EXPECT_EQ(load_bytecode(board.get()), program(10, 1));
}

TEST(Store, RefusesToLoadIntoASmallerArray)
{
    auto board = new_board();
    ASSERT_TRUE(save_bytecode(board.get(), program(100, 1)));
    Words words(99);
    uint16_t count = 0;
    EXPECT_FALSE(store_load_bytecode(board.get(), words.data(), 99, &count));
}

TEST(Store, SettingsAndBytecodeAreIndependent)
{
    auto board = new_board();
    Words settings{ 7, 1, 2, 3 };
    ASSERT_TRUE(save_bytecode(board.get(), program(300, 5)));
    ASSERT_TRUE(store_save_settings(board.get(), settings.data(), 4));
    ASSERT_TRUE(save_bytecode(board.get(), program(200, 6)));
    Words loaded(STORE_SETTINGS_WORDS);
    uint16_t count = 0;
    ASSERT_TRUE(store_load_settings(board.get(), loaded.data(), 44, &count));
    loaded.resize(count);
    EXPECT_EQ(loaded, settings);
    EXPECT_EQ(load_bytecode(board.get()), program(200, 6));
}

TEST(NodeId, ComesFromTheSettingsOrElseFromTheSelector)
{
    // Hardware §6.6: without settings, (selector & 7) + 1.
    auto board = new_board();
    EXPECT_EQ(store_node_id(board.get(), epuck_selector_node_id(0)), 1);
    EXPECT_EQ(store_node_id(board.get(), epuck_selector_node_id(13)), 6);
    // Settings word 0 is the node id.
    Words settings{ 42, 1, 2 };
    ASSERT_TRUE(store_save_settings(board.get(), settings.data(), 3));
    EXPECT_EQ(store_node_id(board.get(), epuck_selector_node_id(13)), 42);
    // Not a node id (0, the broadcast 0xFFFF) or an empty record: the selector.
    for (Words other : { Words{ 0, 5 }, Words{ 0xFFFF }, Words{} }) {
        ASSERT_TRUE(
          store_save_settings(board.get(), other.data(), static_cast<uint16_t>(other.size())));
        EXPECT_EQ(store_node_id(board.get(), epuck_selector_node_id(2)), 3);
    }
    Words highest{ 0xFFFE };
    ASSERT_TRUE(store_save_settings(board.get(), highest.data(), 1));
    EXPECT_EQ(store_node_id(board.get(), epuck_selector_node_id(2)), 0xFFFE);
}

TEST(Store, ReadsSlotsWrittenFromTheDocumentedFormat)
{
    auto board = new_board();
    write_slot(board.get(), STORE_BYTECODE_SLOT_1, STORE_MAGIC_BYTECODE, 9, program(77, 3));
    EXPECT_EQ(load_bytecode(board.get()), program(77, 3));
    // A settings record is not a program.
    auto other = new_board();
    write_slot(other.get(), STORE_BYTECODE_SLOT_0, STORE_MAGIC_SETTINGS, 9, program(7, 3));
    EXPECT_FALSE(load_bytecode(other.get()).has_value());
}

TEST(Store, PicksTheNewestSequenceAcrossTheWrap)
{
    struct Case {
        uint16_t sequence0, sequence1;
        int newest;
    };
    for (Case c : { Case{ 1, 2, 1 },
                    Case{ 2, 1, 0 },
                    Case{ 0xFFFF, 0, 1 },
                    Case{ 0, 0xFFFF, 0 },
                    Case{ 0x7FFF, 0x8000, 1 },
                    Case{ 0xFFFE, 0xFFFF, 1 } }) {
        auto board = new_board();
        write_slot(
          board.get(), STORE_BYTECODE_SLOT_0, STORE_MAGIC_BYTECODE, c.sequence0, program(20, 0));
        write_slot(
          board.get(), STORE_BYTECODE_SLOT_1, STORE_MAGIC_BYTECODE, c.sequence1, program(20, 1));
        EXPECT_EQ(load_bytecode(board.get()), program(20, static_cast<uint16_t>(c.newest)))
          << c.sequence0 << " " << c.sequence1;
    }
}

TEST(Store, SavingAfterTheWrapReplacesTheOlderSlot)
{
    auto board = new_board();
    write_slot(board.get(), STORE_BYTECODE_SLOT_0, STORE_MAGIC_BYTECODE, 0xFFFE, program(20, 0));
    write_slot(board.get(), STORE_BYTECODE_SLOT_1, STORE_MAGIC_BYTECODE, 0xFFFF, program(20, 1));
    for (uint16_t seed = 2; seed < 6; seed++) { // sequences 0, 1, 2, 3
        ASSERT_TRUE(save_bytecode(board.get(), program(30, seed)));
        EXPECT_EQ(load_bytecode(board.get()), program(30, seed));
    }
}

// Flips each bit of the header and of the first payload bytes of the newest
// slot: the store falls back to the other slot.
TEST(Store, IgnoresASlotWithAFlippedBit)
{
    auto board = new_board();
    ASSERT_TRUE(save_bytecode(board.get(), program(40, 1))); // slot 0
    ASSERT_TRUE(save_bytecode(board.get(), program(40, 2))); // slot 1, newest
    uint32_t first = STORE_BYTECODE_SLOT_1 / 2;
    const uint32_t stream_bytes = 8 + 40 * 2; // the padding after it is not checked
    for (uint32_t instruction = 0; instruction * 3 < stream_bytes; instruction++) {
        for (uint32_t bit = 0; bit < 24 && instruction * 3 + bit / 8 < stream_bytes; bit++) {
            auto damaged = reboot(*board);
            damaged->flash[first + instruction] ^= 1u << bit;
            EXPECT_EQ(load_bytecode(damaged.get()), program(40, 1))
              << "instruction " << instruction << " bit " << bit;
        }
    }
}

// Counts the erase/write operations of one save.
uint32_t operations_of_save(const hal_board &start, const Words &words)
{
    auto board = reboot(start);
    uint32_t before = board->memory_operations;
    EXPECT_TRUE(save_bytecode(board.get(), words));
    return board->memory_operations - before;
}

// Cuts the power at each operation of a save of `next` on a board that
// holds `before`, reboots, and expects the old or the new program, whole;
// then a second save after the reboot must succeed.
void cut_at_every_operation(const hal_board &start,
                            const std::optional<Words> &old,
                            const Words &next)
{
    uint32_t operations = operations_of_save(start, next);
    ASSERT_GT(operations, 1u);
    bool saw_old = false;
    for (uint32_t cut = 1; cut <= operations; cut++) {
        auto board = reboot(start);
        host_board_cut_power_at(board.get(), cut);
        EXPECT_FALSE(save_bytecode(board.get(), next)) << "cut at " << cut;
        auto rebooted = reboot(*board);
        auto loaded = load_bytecode(rebooted.get());
        if (old.has_value()) {
            ASSERT_TRUE(loaded.has_value()) << "no program after a cut at " << cut;
            EXPECT_TRUE(*loaded == *old || *loaded == next) << "cut at " << cut;
            saw_old = saw_old || *loaded == *old;
        } else if (loaded.has_value()) {
            EXPECT_EQ(*loaded, next) << "cut at " << cut;
        }
        // A cut during a second save, right after the reboot, keeps it safe too.
        auto again = reboot(*rebooted);
        host_board_cut_power_at(again.get(), cut);
        save_bytecode(again.get(), program(90, 77));
        auto after_two = reboot(*again);
        auto loaded_two = load_bytecode(after_two.get());
        if (loaded.has_value()) {
            ASSERT_TRUE(loaded_two.has_value()) << "cut twice at " << cut;
            EXPECT_TRUE(*loaded_two == *loaded || *loaded_two == program(90, 77));
        }
        ASSERT_TRUE(save_bytecode(after_two.get(), next));
        EXPECT_EQ(load_bytecode(after_two.get()), next);
    }
    if (old.has_value()) {
        EXPECT_TRUE(saw_old); // the cuts did interrupt the save
    }
}

TEST(PowerCut, DuringTheFirstSaveLeavesNothingOrTheNewProgram)
{
    auto board = new_board();
    cut_at_every_operation(*board, std::nullopt, program(1024, 1));
}

TEST(PowerCut, DuringASaveOverOneProgramKeepsOldOrNew)
{
    auto board = new_board();
    ASSERT_TRUE(save_bytecode(board.get(), program(600, 1)));
    cut_at_every_operation(*board, program(600, 1), program(1024, 2));
}

TEST(PowerCut, DuringASaveOverTwoProgramsKeepsOldOrNew)
{
    auto board = new_board();
    ASSERT_TRUE(save_bytecode(board.get(), program(1024, 1)));
    ASSERT_TRUE(save_bytecode(board.get(), program(300, 2)));
    cut_at_every_operation(*board, program(300, 2), program(1024, 3));
    // The same when the new program is shorter than the one it replaces.
    cut_at_every_operation(*board, program(300, 2), program(5, 4));
}

TEST(PowerCut, DuringASettingsSaveKeepsOldOrNew)
{
    auto board = new_board();
    Words old{ 1, 2, 3, 4, 5 };
    Words next{ 6, 7, 8 };
    ASSERT_TRUE(store_save_settings(board.get(), old.data(), 5));
    for (uint32_t cut = 1; cut <= 2; cut++) { // one erase, one write
        auto cut_board = reboot(*board);
        host_board_cut_power_at(cut_board.get(), cut);
        EXPECT_FALSE(store_save_settings(cut_board.get(), next.data(), 3));
        auto rebooted = reboot(*cut_board);
        Words loaded(44);
        uint16_t count = 0;
        ASSERT_TRUE(store_load_settings(rebooted.get(), loaded.data(), 44, &count));
        loaded.resize(count);
        // The cut write programs the first half of the row, which holds this
        // whole short record: it may already be complete.
        EXPECT_TRUE(loaded == old || (cut == 2 && loaded == next)) << "cut at " << cut;
    }
}

} // namespace
