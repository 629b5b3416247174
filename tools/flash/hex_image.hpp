// Firmware images for the Aseba bootloader: Intel HEX files as the Microchip
// tools write them for the dsPIC (hardware fact sheet §4.4), turned into the
// 128-byte pages that the bootloader writes (bootloader/bootloader.h).
//
// In such a file every 24-bit instruction takes 4 bytes (low, middle, upper,
// then a zero "phantom" byte) at byte address 2 x its PC address. Data EEPROM
// (byte addresses 0xFFE000-0xFFFFFF) and configuration words (from
// 0x1F00000) are counted and skipped as the bootloader only writes program
// flash; the configuration words are kept aside for the images that a
// programmer writes (write_microchip_hex).

#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
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
    std::map<uint32_t, uint32_t> instructions;  // PC address -> 24-bit instruction
    std::size_t skipped_bytes = 0;              // EEPROM and configuration data
    std::map<uint32_t, uint16_t> configuration; // PC address (0xF80000..) -> configuration word
};

// Reads `text`; throws HexError for a malformed record (syntax, checksum,
// unknown type, a length or address that splits an instruction, a non-zero
// phantom byte, no end-of-file record), for records that give the same
// instruction twice, or for program data outside [0, application_end) (PC
// addresses).
ProgramImage read_microchip_hex(std::string_view text, uint32_t application_end);

// Reads the HEX file at `path` as read_microchip_hex reads text; the what()
// of the HexError it throws starts with the path (a file that cannot be
// read, or the faulty line).
ProgramImage read_microchip_hex_file(const std::string &path, uint32_t application_end);

inline constexpr std::size_t page_bytes = 128; // one flash row
inline constexpr uint32_t page_span = 0x40;    // PC units per page
inline constexpr uint32_t erased_instruction = 0xFFFFFF;

struct Page {
    uint16_t number; // PC address / page_span
    std::array<uint8_t, page_bytes> bytes;
};

// Adds the descriptor that the bootloader checks before it starts the
// application (bootloader/boot_application.h) to an application image,
// which starts at BOOT_APPLICATION_START (0x100, its GOTO table). The entry
// is `entry` when given (a synthetic image), else BOOT_APPLICATION_ENTRY,
// the table's reset slot, which must hold a GOTO (to the application's
// start-up code). End after the highest instruction below the descriptor,
// CRC of [0x100, end) with missing instructions erased. Throws HexError when
// the image has instructions below 0x100 (they belong to the bootloader
// image), has no reset slot, has an entry outside [0x100, end) or at or above
// BOOT_ENTRY_LIMIT, or when the code reaches the descriptor's row.
void add_application_descriptor(ProgramImage &image, std::optional<uint32_t> entry = {});

// The pages to write, in increasing order: every page from BOOT_PAGES_START
// (the application's first row) to the end of the code, then the pages above
// it that hold data (the descriptor); missing instructions are erased
// (0xFFFFFF), phantom bytes 0. Writing all of them leaves flash exactly as
// the descriptor's CRC expects. Instructions below the first page are not
// written (add_application_descriptor refuses such an image).
std::vector<Page> make_pages(const ProgramImage &image);

// Checks an application image as the bootloader will once it is written
// (make_pages): the descriptor is there, its entry and end are in range, and
// its CRC matches the instructions. Throws HexError saying what is wrong;
// flashing tools call it before they take any robot out of service.
void check_application_image(const ProgramImage &image);

// `image` with every instruction of the pages make_pages writes present,
// missing ones as erased (0xFFFFFF): written as HEX, it has no gaps, so a
// tool that fills missing bytes with zeros (asebacmd whex) or skips pages
// without data writes the same flash as make_pages.
ProgramImage fill_pages(const ProgramImage &image);

// `image` as Microchip's bin2hex writes Intel HEX: an extended linear
// address record (type 04) before the first data record of every 64 KB of
// hex addresses, data records (type 00) of up to 16 bytes that neither cross
// a 16-byte boundary nor span a gap, 4 bytes per instruction (phantom 0) at
// 2 x PC, configuration words as 2 bytes and 2 zero bytes, upper-case
// digits, one record per line (LF), then the end-of-file record. Reading the text
// back gives the same instructions and configuration words.
std::string write_microchip_hex(const ProgramImage &image);

} // namespace aseba::flash
