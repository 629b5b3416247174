// Row packets for the factory Tiny Bootloader (fact sheet §4.2-4.3).

#include "tools/flash/tiny_bootloader.hpp"

extern "C" {
#include "bootloader/boot_application.h"
}

namespace aseba::flash
{
namespace
{

constexpr uint32_t row_span = 0x40;
constexpr uint32_t row_instructions = 32;
constexpr uint32_t pc_units_per_instruction = 2;
constexpr uint8_t payload_length = 0x60; // 96 bytes: the packet's 4th byte
constexpr std::size_t payload_offset = 4;
constexpr uint32_t robot_id_address = 0x017F36;
constexpr uint32_t trampoline_address = 0x017F38;
constexpr uint8_t end_marker = 0xFF;

// GOTO `target` as its two instructions (fact sheet §4.1: GOTO 0x017F40 is
// 0x047F40, 0x000001).
std::array<uint32_t, 2> goto_instructions(uint32_t target)
{
    return { BOOT_GOTO_OPCODE << 16 | (target & 0xFFFE), (target >> 16) & BOOT_GOTO_HIGH_MASK };
}

TinyPacket make_packet(uint32_t row_address, const std::array<uint32_t, row_instructions> &row)
{
    TinyPacket packet{};
    packet[0] = static_cast<uint8_t>(row_address);
    packet[1] = static_cast<uint8_t>(row_address >> 8);
    packet[2] = static_cast<uint8_t>(row_address >> 16);
    packet[3] = payload_length;
    for (uint32_t i = 0; i < row_instructions; i++) {
        for (uint32_t b = 0; b < 3; b++)
            packet[payload_offset + 3 * i + b] = static_cast<uint8_t>(row[i] >> (8 * b));
    }
    uint8_t sum = 0;
    for (std::size_t i = 0; i + 1 < packet.size(); i++)
        sum = static_cast<uint8_t>(sum + packet[i]);
    packet.back() = static_cast<uint8_t>(-sum); // the 101 bytes sum to 0
    return packet;
}

} // namespace

std::vector<TinyPacket> tiny_bootloader_packets(const ProgramImage &image, uint16_t robot_id)
{
    auto instruction_at = [&](uint32_t pc) {
        auto found = image.instructions.find(pc);
        return found == image.instructions.end() ? erased_instruction : found->second;
    };
    if (image.instructions.empty() || instruction_at(0) >> 16 != BOOT_GOTO_OPCODE)
        throw HexError("PC 0 holds no GOTO: the image has no reset vector");
    if (image.instructions.rbegin()->first >= tiny_bootloader_base)
        throw HexError("the image reaches the Tiny Bootloader's row at 0x17F00");
    uint32_t entry = (instruction_at(0) & 0xFFFF) | (instruction_at(2) & BOOT_GOTO_HIGH_MASK) << 16;

    std::vector<TinyPacket> packets;
    uint32_t last_row = image.instructions.rbegin()->first / row_span;
    for (uint32_t number = 0; number <= last_row; number++) {
        std::array<uint32_t, row_instructions> row{};
        for (uint32_t i = 0; i < row_instructions; i++)
            row[i] = instruction_at(number * row_span + i * pc_units_per_instruction);
        if (number == 0) { // reset: into the Tiny Bootloader first
            auto vector = goto_instructions(tiny_bootloader_entry);
            row[0] = vector[0];
            row[1] = vector[1];
        }
        packets.push_back(make_packet(number * row_span, row));
    }
    std::array<uint32_t, row_instructions> trampoline;
    trampoline.fill(erased_instruction);
    trampoline[(robot_id_address - tiny_bootloader_base) / pc_units_per_instruction] = robot_id;
    auto jump = goto_instructions(entry);
    uint32_t first = (trampoline_address - tiny_bootloader_base) / pc_units_per_instruction;
    trampoline[first] = jump[0];
    trampoline[first + 1] = jump[1];
    packets.push_back(make_packet(tiny_bootloader_base, trampoline));
    return packets;
}

std::array<uint8_t, 4> tiny_bootloader_end(uint16_t led_ticks)
{
    return {
        static_cast<uint8_t>(led_ticks), static_cast<uint8_t>(led_ticks >> 8), 0x00, end_marker
    };
}

} // namespace aseba::flash
