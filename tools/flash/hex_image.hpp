// Firmware images for the Aseba bootloader: Intel HEX files as the Microchip
// tools write them for the dsPIC (hardware fact sheet §4.4), turned into the
// 128-byte pages that the bootloader writes (bootloader/bootloader.h).
//
// In such a file every 24-bit instruction takes 4 bytes (low, middle, upper,
// then a zero "phantom" byte) at byte address 2 x its PC address. Data EEPROM
// (byte addresses 0xFFE000-0xFFFFFF) and configuration words (from
// 0x1F00000) are counted and skipped: the bootloader only writes program
// flash.

#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace aseba::flash
{

// A HEX file the bootloader cannot take; what() names the line and the fault.
struct HexError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Program memory read from a HEX file.
struct ProgramImage {
    std::map<uint32_t, uint32_t> instructions; // PC address -> 24-bit instruction
    std::size_t skipped_bytes = 0;             // EEPROM and configuration data
};

// Reads `text`; throws HexError for a malformed record (syntax, checksum,
// unknown type, a length or address that splits an instruction, a non-zero
// phantom byte, no end-of-file record) or for program data outside
// [0, application_end) (PC addresses).
ProgramImage read_microchip_hex(std::string_view text, uint32_t application_end);

inline constexpr std::size_t page_bytes = 128; // one flash row
inline constexpr uint32_t page_span = 0x40;    // PC units per page
inline constexpr uint32_t erased_instruction = 0xFFFFFF;

struct Page {
    uint16_t number; // PC address / page_span
    std::array<uint8_t, page_bytes> bytes;
};

// Adds the descriptor that the bootloader checks before it starts the
// application (bootloader/boot_application.h): entry from the reset GOTO at
// PC 0 unless `entry` is given (an image that also holds the bootloader,
// whose GOTO leads there), end after the highest instruction below the
// descriptor, CRC of [4, end) with missing instructions erased. Throws
// HexError when there is no entry or the code reaches the descriptor's row.
void add_application_descriptor(ProgramImage &image, std::optional<uint32_t> entry = {});

// The pages to write, in increasing order: every page from 0 to the end of
// the code, then the pages above it that hold data (the descriptor);
// missing instructions are erased (0xFFFFFF), phantom bytes 0. Writing all
// of them leaves flash exactly as the descriptor's CRC expects.
std::vector<Page> make_pages(const ProgramImage &image);

} // namespace aseba::flash
