// The first installation of our image through the e-puck's factory Tiny
// Bootloader (hardware fact sheet §4.2-4.3): the 101-byte row packets its
// uploaders send, with the reset vector redirected to the Tiny Bootloader and
// its exit trampoline leading to the image's own entry point.

#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tools/flash/hex_image.hpp"

namespace aseba::flash
{

inline constexpr std::size_t tiny_packet_bytes = 101;
inline constexpr uint32_t tiny_bootloader_base = 0x017F00; // its row, never sent but the trampoline
inline constexpr uint32_t tiny_bootloader_entry = 0x017F40;

using TinyPacket = std::array<uint8_t, tiny_packet_bytes>;

// The packets that install `image` (every row from 0 to its highest
// instruction, then the trampoline row at 0x017F00 holding `robot_id` and a
// GOTO to the image's reset target), in the order the factory uploader sends
// them. Throws HexError when the image has no reset GOTO or reaches the
// Tiny Bootloader's row.
std::vector<TinyPacket> tiny_bootloader_packets(const ProgramImage &image, uint16_t robot_id);

// The 4 bytes that end an upload: LED on for `led_ticks` x about 13.4 ms, then
// the Tiny Bootloader jumps to its trampoline.
std::array<uint8_t, 4> tiny_bootloader_end(uint16_t led_ticks);

} // namespace aseba::flash
