// Intel HEX images as pic30-elf-bin2hex writes them for the dsPIC30F: byte
// address = 2 x PC address, 4 bytes per 24-bit instruction word (low,
// middle, upper, then a "phantom" 0); data EEPROM and configuration words
// the same way, with their 16 bits in the first two bytes.

#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>

namespace aseba::dspic30
{

// A file that is not such an image; what() names the line and the fault.
struct HexError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The program words of `text` by PC address. Throws HexError for a
// malformed record (syntax, length, checksum, unknown type), a record after
// the end-of-file record or no end-of-file record, a word given twice or
// only in part, or a non-zero phantom byte.
std::map<uint32_t, uint32_t> read_intel_hex(std::string_view text);

// The same for the file at `path` (HexError also when it cannot be read).
std::map<uint32_t, uint32_t> read_intel_hex_file(const std::string &path);

} // namespace aseba::dspic30
