// The memory file's format and its atomic replacement (temporary file,
// fsync, rename, fsync of the folder).

#include "tools/dspic30_sim/memory_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <sys/stat.h>
#include <unistd.h>

namespace aseba::dspic30
{
namespace
{

constexpr char header[] = "dspic30-sim memory 1 (dsPIC30F6014A: flash, EEPROM, configuration)\n";
constexpr std::size_t header_size = sizeof header - 1;
constexpr std::size_t flash_word_bytes = 3, data_word_bytes = 2, crc_bytes = 4;
constexpr std::size_t file_size = header_size + flash_words * flash_word_bytes +
                                  eeprom_words * data_word_bytes + config_words * data_word_bytes +
                                  crc_bytes;

// CRC-32 (the IEEE 802.3 polynomial, reflected, as zlib's crc32).
uint32_t crc32(const uint8_t *data, std::size_t size)
{
    uint32_t crc = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int bit = 0; bit < 8; ++bit)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void put(std::vector<uint8_t> &out, uint32_t value, std::size_t bytes)
{
    for (std::size_t i = 0; i < bytes; ++i)
        out.push_back(static_cast<uint8_t>(value >> (8 * i)));
}

uint32_t get(const uint8_t *&in, std::size_t bytes)
{
    uint32_t value = 0;
    for (std::size_t i = 0; i < bytes; ++i)
        value |= static_cast<uint32_t>(*in++) << (8 * i);
    return value;
}

std::string system_error(const std::string &what)
{
    return what + ": " + std::strerror(errno);
}

} // namespace

NonVolatileMemory capture_memory(const ProgramMemory &memory)
{
    NonVolatileMemory contents;
    contents.flash.resize(flash_words);
    contents.eeprom.resize(eeprom_words);
    for (uint32_t i = 0; i < flash_words; ++i)
        contents.flash[i] = memory.read(2 * i);
    for (uint32_t i = 0; i < eeprom_words; ++i)
        contents.eeprom[i] = static_cast<uint16_t>(memory.read(eeprom_base + 2 * i));
    for (uint32_t i = 0; i < config_words; ++i)
        contents.config[i] = static_cast<uint16_t>(memory.read(config_base + 2 * i));
    return contents;
}

void restore_memory(Cpu &cpu, const NonVolatileMemory &contents)
{
    for (uint32_t i = 0; i < flash_words; ++i)
        cpu.program(2 * i, contents.flash[i]);
    for (uint32_t i = 0; i < eeprom_words; ++i)
        cpu.program(eeprom_base + 2 * i, contents.eeprom[i]);
    for (uint32_t i = 0; i < config_words; ++i)
        cpu.program(config_base + 2 * i, contents.config[i]);
}

NonVolatileMemory read_memory_file(const std::string &path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
        throw MemoryFileError(system_error(path + ": cannot read"));
    const std::vector<uint8_t> bytes{ std::istreambuf_iterator<char>(file),
                                      std::istreambuf_iterator<char>() };
    if (bytes.size() < header_size || std::memcmp(bytes.data(), header, header_size) != 0)
        throw MemoryFileError(path + ": not a dspic30-sim memory file");
    if (bytes.size() != file_size)
        throw MemoryFileError(path + ": " + std::to_string(bytes.size()) +
                              " bytes where a memory file has " + std::to_string(file_size) +
                              " (truncated or damaged)");
    const uint8_t *in = bytes.data() + file_size - crc_bytes;
    if (get(in, crc_bytes) != crc32(bytes.data(), file_size - crc_bytes))
        throw MemoryFileError(path + ": its checksum does not match (damaged)");
    NonVolatileMemory contents;
    in = bytes.data() + header_size;
    for (uint32_t i = 0; i < flash_words; ++i)
        contents.flash.push_back(get(in, flash_word_bytes));
    for (uint32_t i = 0; i < eeprom_words; ++i)
        contents.eeprom.push_back(static_cast<uint16_t>(get(in, data_word_bytes)));
    for (uint16_t &word : contents.config)
        word = static_cast<uint16_t>(get(in, data_word_bytes));
    return contents;
}

void write_memory_file(const std::string &path, const NonVolatileMemory &contents)
{
    std::vector<uint8_t> bytes(header, header + header_size);
    for (uint32_t word : contents.flash)
        put(bytes, word, flash_word_bytes);
    for (uint16_t word : contents.eeprom)
        put(bytes, word, data_word_bytes);
    for (uint16_t word : contents.config)
        put(bytes, word, data_word_bytes);
    put(bytes, crc32(bytes.data(), bytes.size()), crc_bytes);

    std::string temporary = path + ".XXXXXX";
    const int fd = mkstemp(temporary.data());
    if (fd < 0)
        throw MemoryFileError(system_error(path + ": cannot write beside it"));
    // mkstemp's file is private; the memory file gets the mode of the one it
    // replaces, else the usual one (0666 less the umask).
    struct stat old {
    };
    if (stat(path.c_str(), &old) == 0) {
        fchmod(fd, old.st_mode & 07777);
    } else {
        const mode_t mask = umask(0);
        umask(mask);
        fchmod(fd, 0666 & ~mask);
    }
    std::size_t written = 0;
    while (written < bytes.size()) {
        const ssize_t n = write(fd, bytes.data() + written, bytes.size() - written);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            break;
        written += static_cast<std::size_t>(n);
    }
    const bool ok = written == bytes.size() && fsync(fd) == 0;
    const std::string failure = system_error(path + ": cannot write");
    close(fd);
    if (!ok || std::rename(temporary.c_str(), path.c_str()) != 0) {
        std::remove(temporary.c_str());
        throw MemoryFileError(ok ? system_error(path + ": cannot replace") : failure);
    }
    // The rename itself reaches the disk with its folder.
    const std::size_t slash = path.rfind('/');
    const std::string folder = slash == std::string::npos ? "." : path.substr(0, slash + 1);
    const int folder_fd = open(folder.c_str(), O_RDONLY | O_DIRECTORY);
    if (folder_fd >= 0) {
        fsync(folder_fd);
        close(folder_fd);
    }
}

} // namespace aseba::dspic30
