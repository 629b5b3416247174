// A simulated e-puck's memories before power-on (see robot_memory.hpp).

#include "robot_memory.hpp"

#include <array>
#include <cstdio>
#include <stdexcept>
#include <sys/stat.h>

extern "C" {
#include "bootloader/boot_application.h"
#include "bootloader/bytecode_store.h"
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
    if (bytecode.size() > EPUCK_BYTECODE_WORDS ||
        !epuck_store_save_bytecode(&board, bytecode.data(), uint16_t(bytecode.size())))
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

void save_memories(const hal_board &board, const std::string &path)
{
    std::string temporary = path + ".partial";
    if (!host_board_save_memory(&board, temporary.c_str()) ||
        std::rename(temporary.c_str(), path.c_str()) != 0) {
        std::remove(temporary.c_str());
        throw std::runtime_error(path + ": the robot's memory could not be saved");
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
    host_robot_start_application(&robot);
}

} // namespace aseba::host
