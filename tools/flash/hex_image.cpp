// Reads Microchip Intel HEX files and cuts them into bootloader pages.

#include "tools/flash/hex_image.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <string>

extern "C" {
#include "bootloader/boot_application.h"
#include "bootloader/bootloader.h"
#include "vm/node.h"
}

namespace aseba::flash
{
namespace
{

constexpr uint8_t record_data = 0x00;
constexpr uint8_t record_end_of_file = 0x01;
constexpr uint8_t record_extended_linear_address = 0x04;
constexpr std::size_t record_overhead = 5; // count, address (2), type, checksum
constexpr uint32_t bytes_per_instruction = 4;
constexpr uint32_t hex_bytes_per_pc_unit = 2;
constexpr uint32_t eeprom_hex_start = 0xFFE000;
constexpr uint32_t eeprom_hex_end = 0x1000000;
constexpr uint32_t config_hex_start = 0x1F00000;
constexpr uint32_t config_hex_end = 0x1F00020; // 8 words, 4 bytes each
constexpr uint32_t pc_units_per_instruction = 2;
constexpr uint32_t configuration_pc_start = config_hex_start / hex_bytes_per_pc_unit;
constexpr uint32_t configuration_pc_end = config_hex_end / hex_bytes_per_pc_unit;
constexpr uint32_t hex_record_max_bytes = 16; // as bin2hex writes them
constexpr uint32_t hex_segment_shift = 16;    // the extended linear address: bits 31:16

std::string hex_number(uint32_t value)
{
    std::ostringstream out;
    out << "0x" << std::hex << std::uppercase << value;
    return out.str();
}

[[noreturn]] void fail(std::size_t line, const std::string &message)
{
    throw HexError("line " + std::to_string(line) + ": " + message);
}

int digit_value(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    return -1;
}

// The bytes of one record line (without the colon), checked for syntax,
// length and checksum.
std::vector<uint8_t> record_bytes(std::string_view line, std::size_t number)
{
    if (line.empty() || line[0] != ':')
        fail(number, "a record must start with ':'");
    line.remove_prefix(1);
    if (line.size() % 2 != 0)
        fail(number, "odd number of hex digits");
    std::vector<uint8_t> bytes;
    for (std::size_t i = 0; i < line.size(); i += 2) {
        int high = digit_value(line[i]);
        int low = digit_value(line[i + 1]);
        if (high < 0 || low < 0)
            fail(number, "not a hex digit");
        bytes.push_back(static_cast<uint8_t>(high * 16 + low));
    }
    if (bytes.size() < record_overhead || bytes.size() != record_overhead + bytes[0])
        fail(number, "the byte count does not match the record's length");
    uint8_t sum = 0;
    for (uint8_t byte : bytes)
        sum = static_cast<uint8_t>(sum + byte);
    if (sum != 0)
        fail(number, "bad checksum");
    return bytes;
}

// The line of the HEX file that gave each program instruction, to find
// records that overlap.
using LineOfInstruction = std::map<uint32_t, std::size_t>;

void add_data(ProgramImage &image,
              LineOfInstruction &line_of,
              uint32_t hex_address,
              const uint8_t *data,
              std::size_t count,
              uint32_t application_end,
              std::size_t number)
{
    uint32_t hex_end = hex_address + static_cast<uint32_t>(count);
    if (hex_address >= eeprom_hex_start && hex_end <= eeprom_hex_end) {
        image.skipped_bytes += count;
        return;
    }
    if (hex_address >= config_hex_start && hex_end <= config_hex_end) {
        image.skipped_bytes += count;
        // Each word is 2 bytes then 2 zero bytes; keep the whole ones.
        for (std::size_t i = 0; i + bytes_per_instruction <= count; i += bytes_per_instruction) {
            uint32_t at = hex_address + static_cast<uint32_t>(i);
            if (at % bytes_per_instruction == 0)
                image.configuration[at / hex_bytes_per_pc_unit] =
                  static_cast<uint16_t>(data[i] | data[i + 1] << 8);
        }
        return;
    }
    if (hex_address % bytes_per_instruction != 0 || count % bytes_per_instruction != 0)
        fail(number,
             "program data must be whole 4-byte instructions (address " + hex_number(hex_address) +
               ", " + std::to_string(count) + " bytes)");
    for (std::size_t i = 0; i < count; i += bytes_per_instruction) {
        uint32_t pc = (hex_address + static_cast<uint32_t>(i)) / hex_bytes_per_pc_unit;
        if (pc >= application_end)
            fail(number,
                 "PC address " + hex_number(pc) + " is outside the application region [0, " +
                   hex_number(application_end) + ")");
        if (data[i + 3] != 0)
            fail(number, "non-zero phantom byte at PC address " + hex_number(pc));
        // The last record would silently win: refuse the image instead.
        if (auto [earlier, added] = line_of.emplace(pc, number); !added)
            fail(number,
                 "PC address " + hex_number(pc) + " was given already on line " +
                   std::to_string(earlier->second) + ": records overlap");
        image.instructions[pc] =
          static_cast<uint32_t>(data[i] | (data[i + 1] << 8) | (data[i + 2] << 16));
    }
}

} // namespace

ProgramImage read_microchip_hex(std::string_view text, uint32_t application_end)
{
    ProgramImage image;
    LineOfInstruction line_of;
    uint32_t upper_address = 0;
    bool ended = false;
    std::size_t number = 0;

    while (!text.empty()) {
        std::size_t newline = text.find('\n');
        std::string_view line = text.substr(0, newline);
        text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
        number++;
        if (!line.empty() && line.back() == '\r')
            line.remove_suffix(1);
        if (line.empty())
            continue;
        if (ended)
            fail(number, "record after the end-of-file record");
        std::vector<uint8_t> bytes = record_bytes(line, number);
        uint8_t count = bytes[0];
        uint32_t offset = static_cast<uint32_t>(bytes[1] << 8 | bytes[2]);
        const uint8_t *data = bytes.data() + 4;
        switch (bytes[3]) {
        case record_data:
            add_data(
              image, line_of, upper_address << 16 | offset, data, count, application_end, number);
            break;
        case record_end_of_file:
            if (count != 0)
                fail(number, "end-of-file record with data");
            ended = true;
            break;
        case record_extended_linear_address:
            if (count != 2)
                fail(number, "extended linear address record must hold 2 bytes");
            upper_address = static_cast<uint32_t>(data[0] << 8 | data[1]);
            break;
        default:
            fail(number,
                 "unsupported record type " + std::to_string(bytes[3]) +
                   " (Microchip files use 00, 01 and 04)");
        }
    }
    if (!ended)
        throw HexError("no end-of-file record: the file is truncated");
    return image;
}

ProgramImage read_microchip_hex_file(const std::string &path, uint32_t application_end)
{
    std::error_code ignored;
    if (std::filesystem::is_directory(path, ignored))
        throw HexError(path + ": is a folder, not a HEX file");
    std::ifstream file(path, std::ios::binary);
    if (!file)
        throw HexError(path + ": cannot be read (" + std::strerror(errno) + ")");
    std::ostringstream text;
    text << file.rdbuf();
    if (file.bad())
        throw HexError(path + ": cannot be read (" + std::strerror(errno) + ")");
    try {
        return read_microchip_hex(text.str(), application_end);
    } catch (const HexError &error) {
        throw HexError(path + ": " + error.what());
    }
}

namespace
{

uint32_t instruction_at(const ProgramImage &image, uint32_t pc)
{
    auto found = image.instructions.find(pc);
    return found == image.instructions.end() ? erased_instruction : found->second;
}

// What the bootloader computes over [BOOT_CHECKED_START, end) once the image
// is written (missing instructions erased).
uint16_t application_crc(const ProgramImage &image, uint32_t end)
{
    uint16_t crc = 0;
    for (uint32_t pc = BOOT_CHECKED_START; pc < end; pc += pc_units_per_instruction) {
        uint32_t value = instruction_at(image, pc);
        uint8_t bytes[3] = { static_cast<uint8_t>(value),
                             static_cast<uint8_t>(value >> 8),
                             static_cast<uint8_t>(value >> 16) };
        crc = node_crc16(crc, bytes, 3);
    }
    return crc;
}

} // namespace

void add_application_descriptor(ProgramImage &image, std::optional<uint32_t> entry)
{
    if (!image.instructions.empty() && image.instructions.begin()->first < BOOT_APPLICATION_START)
        throw HexError("PC address " + hex_number(image.instructions.begin()->first) +
                       " is below the application's start " + hex_number(BOOT_APPLICATION_START) +
                       ": rows 0-3 belong to the bootloader image (link the application with "
                       "linker/epuck-app.gld)");
    if (!entry.has_value()) {
        if (instruction_at(image, BOOT_APPLICATION_ENTRY) >> 16 != BOOT_GOTO_OPCODE)
            throw HexError("PC " + hex_number(BOOT_APPLICATION_ENTRY) +
                           " holds no GOTO: the application has no reset slot");
        entry = BOOT_APPLICATION_ENTRY;
    }
    auto code_end = image.instructions.lower_bound(BOOT_DESCRIPTOR_ADDRESS);
    if (code_end == image.instructions.begin())
        throw HexError("the image holds no application code");
    uint32_t end = std::prev(code_end)->first + pc_units_per_instruction;
    if (code_end != image.instructions.end() && code_end->first < BOOT_APPLICATION_END)
        throw HexError("the code reaches the descriptor row at " +
                       hex_number(BOOT_DESCRIPTOR_ADDRESS));
    if (*entry < BOOT_APPLICATION_START || *entry >= end || *entry >= BOOT_ENTRY_LIMIT ||
        *entry % pc_units_per_instruction != 0)
        throw HexError("the entry " + hex_number(*entry) + " is not an even address in [" +
                       hex_number(BOOT_APPLICATION_START) + ", " +
                       hex_number(std::min<uint32_t>(end, BOOT_ENTRY_LIMIT)) + ")");
    uint16_t crc = application_crc(image, end);
    uint32_t base = BOOT_DESCRIPTOR_ADDRESS;
    image.instructions[base + BOOT_DESCRIPTOR_MAGIC_INDEX * 2] = BOOT_DESCRIPTOR_MAGIC;
    image.instructions[base + BOOT_DESCRIPTOR_ENTRY_INDEX * 2] = *entry;
    image.instructions[base + BOOT_DESCRIPTOR_END_INDEX * 2] = end;
    image.instructions[base + BOOT_DESCRIPTOR_CRC_INDEX * 2] = crc;
}

std::vector<Page> make_pages(const ProgramImage &image)
{
    std::vector<Page> pages;
    if (image.instructions.empty())
        return pages;
    // Every page up to the end of the code, so that no old row stays inside
    // the CRC's range; above it (the descriptor), only the pages with data.
    auto code_end = image.instructions.lower_bound(BOOT_DESCRIPTOR_ADDRESS);
    std::vector<uint32_t> numbers;
    if (code_end != image.instructions.begin()) {
        uint32_t last_code_page = std::prev(code_end)->first / page_span;
        for (uint32_t number = BOOT_PAGES_START; number <= last_code_page; number++)
            numbers.push_back(number);
    }
    for (auto it = code_end; it != image.instructions.end(); ++it) {
        if (numbers.empty() || it->first / page_span != numbers.back())
            numbers.push_back(it->first / page_span);
    }
    for (uint32_t number : numbers) {
        Page page{ static_cast<uint16_t>(number), {} };
        for (uint32_t i = 0; i < page_bytes / bytes_per_instruction; i++) {
            auto found = image.instructions.find(number * page_span + i * pc_units_per_instruction);
            uint32_t value = found == image.instructions.end() ? erased_instruction : found->second;
            for (uint32_t b = 0; b < 3; b++)
                page.bytes[i * bytes_per_instruction + b] = static_cast<uint8_t>(value >> (8 * b));
            page.bytes[i * bytes_per_instruction + 3] = 0;
        }
        pages.push_back(page);
    }
    return pages;
}

void check_application_image(const ProgramImage &image)
{
    auto descriptor = [&](uint32_t index) {
        return instruction_at(image, BOOT_DESCRIPTOR_ADDRESS + index * pc_units_per_instruction);
    };
    if (descriptor(BOOT_DESCRIPTOR_MAGIC_INDEX) != BOOT_DESCRIPTOR_MAGIC)
        throw HexError("no application descriptor at PC " + hex_number(BOOT_DESCRIPTOR_ADDRESS) +
                       ", so the bootloader would never start this image (flash the application "
                       "image that `make dspic30` writes, which has one)");
    uint32_t entry = descriptor(BOOT_DESCRIPTOR_ENTRY_INDEX);
    uint32_t end = descriptor(BOOT_DESCRIPTOR_END_INDEX);
    uint32_t crc = descriptor(BOOT_DESCRIPTOR_CRC_INDEX);
    // Where the pages the image writes end: beyond, the robot's flash keeps
    // whatever it held, which no check here can know.
    auto code_end = image.instructions.lower_bound(BOOT_DESCRIPTOR_ADDRESS);
    uint32_t written_end = code_end == image.instructions.begin()
                             ? BOOT_APPLICATION_START
                             : (std::prev(code_end)->first / page_span + 1) * page_span;
    if (end <= BOOT_CHECKED_START || end > written_end || end % pc_units_per_instruction != 0)
        throw HexError("the descriptor's end " + hex_number(end) +
                       " is not an even address within the image's code (" +
                       hex_number(BOOT_CHECKED_START) + " to " + hex_number(written_end) + ")");
    if (entry < BOOT_APPLICATION_START || entry >= end || entry >= BOOT_ENTRY_LIMIT ||
        entry % pc_units_per_instruction != 0)
        throw HexError("the descriptor's entry " + hex_number(entry) +
                       " is not an even address in [" + hex_number(BOOT_APPLICATION_START) + ", " +
                       hex_number(std::min<uint32_t>(end, BOOT_ENTRY_LIMIT)) + ")");
    uint16_t computed = application_crc(image, end);
    if (crc != computed)
        throw HexError("the descriptor's CRC is " + hex_number(crc) +
                       " but the image's data give " + hex_number(computed) +
                       ": the bootloader would refuse it and the robots would stay in their "
                       "bootloaders");
}

ProgramImage fill_pages(const ProgramImage &image)
{
    ProgramImage filled = image;
    for (const Page &page : make_pages(image)) {
        for (uint32_t i = 0; i < page_bytes / bytes_per_instruction; i++) {
            const uint8_t *bytes = &page.bytes[i * bytes_per_instruction];
            filled.instructions[page.number * page_span + i * pc_units_per_instruction] =
              static_cast<uint32_t>(bytes[0] | bytes[1] << 8 | bytes[2] << 16);
        }
    }
    return filled;
}

namespace
{

// One Intel HEX record: count, address, type, data, checksum.
std::string hex_record(uint8_t type, uint16_t address, const std::vector<uint8_t> &data)
{
    std::vector<uint8_t> bytes{ static_cast<uint8_t>(data.size()),
                                static_cast<uint8_t>(address >> 8),
                                static_cast<uint8_t>(address),
                                type };
    bytes.insert(bytes.end(), data.begin(), data.end());
    uint8_t sum = 0;
    for (uint8_t byte : bytes)
        sum = static_cast<uint8_t>(sum + byte);
    bytes.push_back(static_cast<uint8_t>(-sum));
    std::ostringstream line;
    line << ':' << std::hex << std::uppercase << std::setfill('0');
    for (uint8_t byte : bytes)
        line << std::setw(2) << static_cast<unsigned>(byte);
    line << '\n';
    return line.str();
}

} // namespace

std::string write_microchip_hex(const ProgramImage &image)
{
    // Every byte of the file at its hex address, in increasing order.
    std::map<uint32_t, uint8_t> bytes;
    for (const auto &[pc, value] : image.instructions) {
        uint32_t at = pc * hex_bytes_per_pc_unit;
        for (uint32_t b = 0; b < 3; b++)
            bytes[at + b] = static_cast<uint8_t>(value >> (8 * b));
        bytes[at + 3] = 0; // the phantom byte
    }
    for (const auto &[pc, value] : image.configuration) {
        if (pc < configuration_pc_start || pc >= configuration_pc_end)
            throw HexError("configuration word at " + hex_number(pc) +
                           " is outside the configuration area");
        uint32_t at = pc * hex_bytes_per_pc_unit;
        bytes[at] = static_cast<uint8_t>(value);
        bytes[at + 1] = static_cast<uint8_t>(value >> 8);
        bytes[at + 2] = 0;
        bytes[at + 3] = 0;
    }
    std::string text;
    std::optional<uint32_t> segment;
    auto it = bytes.begin();
    while (it != bytes.end()) {
        uint32_t start = it->first;
        if (segment != start >> hex_segment_shift) {
            segment = start >> hex_segment_shift;
            text +=
              hex_record(record_extended_linear_address,
                         0,
                         { static_cast<uint8_t>(*segment >> 8), static_cast<uint8_t>(*segment) });
        }
        // A run of consecutive bytes up to the next 16-byte boundary.
        uint32_t limit = (start / hex_record_max_bytes + 1) * hex_record_max_bytes;
        std::vector<uint8_t> data;
        uint32_t next = start;
        while (it != bytes.end() && it->first == next && next < limit) {
            data.push_back(it->second);
            ++it;
            next++;
        }
        text += hex_record(record_data, static_cast<uint16_t>(start), data);
    }
    text += hex_record(record_end_of_file, 0, {});
    return text;
}

} // namespace aseba::flash
