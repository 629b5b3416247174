// Intel HEX records: data (00), end of file (01), extended segment (02) and
// linear (04) addresses; start addresses (03, 05) mean nothing here.

#include "tools/dspic30_sim/intel_hex.hpp"

#include <fstream>
#include <sstream>
#include <vector>

namespace aseba::dspic30
{
namespace
{

constexpr int record_data = 0x00;
constexpr int record_end = 0x01;
constexpr int record_segment = 0x02;
constexpr int record_start_segment = 0x03;
constexpr int record_linear = 0x04;
constexpr int record_start_linear = 0x05;
constexpr std::size_t header_bytes = 4; // length, address high, address low, type
constexpr int bytes_per_word = 4;
constexpr int segment_shift = 4;
constexpr int linear_shift = 16;

int hex_digit(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    return -1;
}

[[noreturn]] void fail(int line, const std::string &what)
{
    throw HexError("line " + std::to_string(line) + ": " + what);
}

} // namespace

std::map<uint32_t, uint32_t> read_intel_hex(std::string_view text)
{
    std::map<uint32_t, uint8_t> bytes; // by byte address
    uint32_t base = 0;
    bool ended = false;
    int line_number = 0;
    std::size_t position = 0;
    while (position < text.size()) {
        std::size_t end = text.find('\n', position);
        if (end == std::string_view::npos)
            end = text.size();
        std::string_view line = text.substr(position, end - position);
        position = end + 1;
        ++line_number;
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
            line.remove_suffix(1);
        if (line.empty())
            continue;
        if (ended)
            fail(line_number, "record after the end-of-file record");
        if (line[0] != ':')
            fail(line_number, "a record starts with ':'");
        if ((line.size() - 1) % 2 != 0)
            fail(line_number, "odd number of hexadecimal digits");
        std::vector<uint8_t> record;
        for (std::size_t i = 1; i < line.size(); i += 2) {
            const int high = hex_digit(line[i]), low = hex_digit(line[i + 1]);
            if (high < 0 || low < 0)
                fail(line_number, "not a hexadecimal digit");
            record.push_back(static_cast<uint8_t>(high * 16 + low));
        }
        if (record.size() < header_bytes + 1)
            fail(line_number, "record too short");
        const std::size_t length = record[0];
        if (record.size() != header_bytes + length + 1)
            fail(line_number,
                 "length field says " + std::to_string(length) + " bytes, the record has " +
                   std::to_string(record.size() - header_bytes - 1));
        uint8_t sum = 0;
        for (uint8_t b : record)
            sum = static_cast<uint8_t>(sum + b);
        if (sum != 0)
            fail(line_number, "checksum mismatch");
        const uint32_t offset = (static_cast<uint32_t>(record[1]) << 8) | record[2];
        const int type = record[3];
        const uint8_t *data = record.data() + header_bytes;
        switch (type) {
        case record_data:
            for (std::size_t i = 0; i < length; ++i) {
                const uint32_t address = base + offset + static_cast<uint32_t>(i);
                if (!bytes.emplace(address, data[i]).second)
                    fail(
                      line_number, "byte address 0x" + [&] {
                          std::ostringstream s;
                          s << std::hex << address;
                          return s.str();
                      }() + " given twice");
            }
            break;
        case record_end: ended = true; break;
        case record_segment:
        case record_linear:
            if (length != 2)
                fail(line_number, "address record of " + std::to_string(length) + " bytes");
            base = ((static_cast<uint32_t>(data[0]) << 8) | data[1])
                   << (type == record_linear ? linear_shift : segment_shift);
            break;
        case record_start_segment:
        case record_start_linear: break;
        default: fail(line_number, "unknown record type " + std::to_string(type));
        }
    }
    if (!ended)
        throw HexError("no end-of-file record");

    std::map<uint32_t, uint32_t> words;
    for (auto it = bytes.begin(); it != bytes.end();) {
        const uint32_t first = it->first & ~static_cast<uint32_t>(bytes_per_word - 1);
        uint8_t b[bytes_per_word];
        for (int i = 0; i < bytes_per_word; ++i) {
            const auto found = bytes.find(first + static_cast<uint32_t>(i));
            std::ostringstream where;
            where << std::hex << "word at byte address 0x" << first;
            if (found == bytes.end())
                throw HexError(where.str() + " (PC 0x" + [&] {
                    std::ostringstream s;
                    s << std::hex << first / 2;
                    return s.str();
                }() + ") given only in part");
            b[i] = found->second;
        }
        if (b[3] != 0) {
            std::ostringstream where;
            where << std::hex << "word at PC 0x" << first / 2
                  << " has a non-zero fourth (phantom) byte";
            throw HexError(where.str());
        }
        words[first / 2] = static_cast<uint32_t>(b[0]) | (static_cast<uint32_t>(b[1]) << 8) |
                           (static_cast<uint32_t>(b[2]) << 16);
        it = bytes.lower_bound(first + bytes_per_word);
    }
    return words;
}

std::map<uint32_t, uint32_t> read_intel_hex_file(const std::string &path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw HexError(path + ": cannot be read");
    std::ostringstream text;
    text << in.rdbuf();
    try {
        return read_intel_hex(text.str());
    } catch (const HexError &e) {
        throw HexError(path + ": " + e.what());
    }
}

} // namespace aseba::dspic30
