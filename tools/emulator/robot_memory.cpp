// A simulated e-puck's memories before power-on (see robot_memory.hpp).

#include "robot_memory.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

extern "C" {
#include "bootloader/boot_application.h"
#include "store/bytecode_store.h"
}

namespace aseba::host
{

flash::ProgramImage placeholder_application()
{
    // In the table's reset slot, a GOTO to itself: the smallest application
    // that never ends.
    constexpr uint32_t entry = BOOT_APPLICATION_ENTRY;
    constexpr uint32_t goto_high_word_address = entry + 2;
    flash::ProgramImage image;
    image.instructions[entry] = uint32_t(BOOT_GOTO_OPCODE) << 16 | (entry & 0xFFFF);
    image.instructions[goto_high_word_address] = (entry >> 16) & BOOT_GOTO_HIGH_MASK;
    flash::add_application_descriptor(image, entry);
    return image;
}

flash::ProgramImage read_application_file(const std::string &path)
{
    return flash::read_microchip_hex_file(path, BOOT_APPLICATION_END);
}

void install_application(hal_board &board, const flash::ProgramImage &image)
{
    for (const flash::Page &page : flash::make_pages(image)) {
        std::array<uint32_t, BOOT_PAGE_WORDS> row;
        for (size_t i = 0; i < row.size(); i++) {
            const uint8_t *bytes = &page.bytes[i * BOOT_BYTES_PER_INSTRUCTION];
            row[i] = uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 | uint32_t(bytes[2]) << 16;
        }
        uint32_t address = uint32_t(page.number) * BOOT_PAGE_SPAN;
        if (!hal_flash_erase(&board, address) ||
            !hal_flash_program(&board, address, row.data(), BOOT_PAGE_WORDS))
            throw std::runtime_error("the simulated flash refused the row at PC " +
                                     std::to_string(address));
    }
}

void store_program(hal_board &board, const std::vector<uint16_t> &bytecode)
{
    if (bytecode.size() > FIRMWARE_BYTECODE_WORDS ||
        !store_save_bytecode(&board, bytecode.data(), uint16_t(bytecode.size())))
        throw std::runtime_error("the program (" + std::to_string(bytecode.size()) +
                                 " words) does not fit in the bytecode store");
}

bool load_memories(hal_board &board, const std::string &path)
{
    struct stat status;
    if (stat(path.c_str(), &status) != 0)
        return false;
    if (!host_board_load_memory(&board, path.c_str()))
        throw std::runtime_error(path + ": not a saved robot memory (wrong size or unreadable)");
    return true;
}

namespace
{

// host_board_save_memory's layout: EEPROM words (2 bytes each), then flash
// instructions (3 bytes each, 24 bits), little-endian.
constexpr size_t eeprom_words = sizeof hal_board::eeprom / sizeof hal_board::eeprom[0];
constexpr size_t flash_words = sizeof hal_board::flash / sizeof hal_board::flash[0];
constexpr size_t eeprom_word_bytes = 2;
constexpr size_t instruction_bytes = 3;
constexpr size_t flash_offset = eeprom_words * eeprom_word_bytes;
// Flash is compared and written in pieces of this many instructions (a row
// of the chip).
constexpr size_t piece_words = 32;

void put_instructions(const uint32_t *words, size_t count, uint8_t *bytes)
{
    for (size_t i = 0; i < count; i++)
        for (size_t b = 0; b < instruction_bytes; b++)
            bytes[i * instruction_bytes + b] = uint8_t(words[i] >> (8 * b));
}

} // namespace

MemoryFile::MemoryFile(const hal_board &board, std::string path)
  : board_(board)
  , path_(std::move(path))
  , operations_seen_(board.memory_operations)
  , eeprom_(std::begin(board.eeprom), std::end(board.eeprom))
  , flash_(std::begin(board.flash), std::end(board.flash))
{
    fd_ = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
        throw std::runtime_error(path_ + ": cannot be opened: " + std::strerror(errno));
    std::vector<uint8_t> bytes(flash_offset + flash_words * instruction_bytes);
    for (size_t i = 0; i < eeprom_words; i++) {
        bytes[i * eeprom_word_bytes] = uint8_t(eeprom_[i]);
        bytes[i * eeprom_word_bytes + 1] = uint8_t(eeprom_[i] >> 8);
    }
    put_instructions(flash_.data(), flash_.size(), bytes.data() + flash_offset);
    write_at(0, bytes.data(), bytes.size());
    if (ftruncate(fd_, off_t(bytes.size())) != 0)
        throw std::runtime_error(path_ + ": cannot be written: " + std::strerror(errno));
}

MemoryFile::~MemoryFile()
{
    if (fd_ >= 0)
        close(fd_);
}

void MemoryFile::write_at(size_t offset, const uint8_t *bytes, size_t count)
{
    while (count > 0) {
        ssize_t written = pwrite(fd_, bytes, count, off_t(offset));
        if (written < 0 && errno == EINTR)
            continue;
        if (written <= 0)
            throw std::runtime_error(path_ + ": cannot be written: " + std::strerror(errno));
        bytes += written;
        offset += size_t(written);
        count -= size_t(written);
    }
}

void MemoryFile::sync()
{
    if (board_.memory_operations == operations_seen_)
        return;
    operations_seen_ = board_.memory_operations;
    for (size_t i = 0; i < eeprom_words; i++) {
        if (board_.eeprom[i] == eeprom_[i])
            continue;
        eeprom_[i] = board_.eeprom[i];
        uint8_t bytes[eeprom_word_bytes] = { uint8_t(eeprom_[i]), uint8_t(eeprom_[i] >> 8) };
        write_at(i * eeprom_word_bytes, bytes, sizeof bytes);
    }
    for (size_t piece = 0; piece < flash_words; piece += piece_words) {
        size_t count = std::min(piece_words, flash_words - piece);
        const uint32_t *now = board_.flash + piece;
        if (std::equal(now, now + count, flash_.begin() + long(piece)))
            continue;
        std::copy(now, now + count, flash_.begin() + long(piece));
        uint8_t bytes[piece_words * instruction_bytes];
        put_instructions(flash_.data() + piece, count, bytes);
        write_at(flash_offset + piece * instruction_bytes, bytes, count * instruction_bytes);
    }
}

void power_on(host_robot &robot,
              const std::function<void(host_robot &)> &prepare,
              const std::vector<uint16_t> &bytecode)
{
    static const flash::ProgramImage placeholder = placeholder_application();
    install_application(robot.board, placeholder);
    if (prepare)
        prepare(robot);
    if (!bytecode.empty())
        store_program(robot.board, bytecode);
    host_robot_power_on(&robot);
}

} // namespace aseba::host
