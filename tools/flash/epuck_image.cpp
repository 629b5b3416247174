// Checks the bootloader image and merges it with the application.

#include "tools/flash/epuck_image.hpp"

#include <sstream>
#include <string>

extern "C" {
#include "bootloader/boot_application.h"
#include "robots/epuck/epuck_flash_layout.h"
}

namespace aseba::flash
{
namespace
{

constexpr uint32_t goto_second_word = 2; // PC units after the GOTO's first word
constexpr uint32_t instruction_high_shift = 16;

std::string hex_number(uint32_t value)
{
    std::ostringstream out;
    out << "0x" << std::hex << std::uppercase << value;
    return out.str();
}

} // namespace

void check_bootloader_image(const ProgramImage &bootloader)
{
    auto instruction_at = [&](uint32_t pc) {
        auto found = bootloader.instructions.find(pc);
        return found == bootloader.instructions.end() ? erased_instruction : found->second;
    };
    for (const auto &[pc, value] : bootloader.instructions) {
        bool vectors = pc < BOOT_APPLICATION_START;
        bool code = pc >= BOOT_LOADER_BASE && pc < BOOT_LOADER_END;
        if (!vectors && !code)
            throw HexError("bootloader image: PC address " + hex_number(pc) +
                           " is outside rows 0-3 and the bootloader region [" +
                           hex_number(BOOT_LOADER_BASE) + ", " + hex_number(BOOT_LOADER_END) + ")");
    }
    uint32_t low = instruction_at(BOOT_VECTORS_BASE);
    uint32_t target =
      (low & 0xFFFF) | (instruction_at(BOOT_VECTORS_BASE + goto_second_word) & BOOT_GOTO_HIGH_MASK)
                         << instruction_high_shift;
    if (low >> instruction_high_shift != BOOT_GOTO_OPCODE || target < BOOT_LOADER_BASE ||
        target >= BOOT_LOADER_END)
        throw HexError("bootloader image: the reset vector is no GOTO into the bootloader region");
    for (uint32_t vector = 0; vector < BOOT_INTERRUPT_COUNT; vector++) {
        uint32_t at = BOOT_IVT_BASE + vector * BOOT_VECTOR_ENTRY_PC;
        if (instruction_at(at) != BOOT_TABLE_INTERRUPT_SLOT(vector))
            throw HexError("bootloader image: IVT entry " + std::to_string(vector) + " at " +
                           hex_number(at) + " does not lead to the application's table slot " +
                           hex_number(BOOT_TABLE_INTERRUPT_SLOT(vector)));
    }
}

ProgramImage merge_images(const ProgramImage &first, const ProgramImage &second)
{
    ProgramImage merged = first;
    for (const auto &[pc, value] : second.instructions) {
        if (!merged.instructions.emplace(pc, value).second)
            throw HexError("both images hold PC address " + hex_number(pc));
    }
    for (const auto &[pc, value] : second.configuration) {
        auto [at, added] = merged.configuration.emplace(pc, value);
        if (!added && at->second != value)
            throw HexError("the images set the configuration word at " + hex_number(pc) +
                           " differently");
    }
    merged.skipped_bytes += second.skipped_bytes;
    return merged;
}

} // namespace aseba::flash
