// The chip's non-volatile memory kept between runs of dspic30-sim
// (--memory FILE): the 48 K flash words, the data EEPROM and the
// configuration words, as the robot keeps them through a power-off. The
// file is the simulator's own: a header line, the words little-endian (3
// bytes a flash word, 2 an EEPROM or configuration word), a CRC-32 of all
// that. It is written whole to a temporary file beside it, then renamed
// over it, so that a simulator killed at any moment leaves the old file or
// the new one, never a mixture.

#pragma once

#include "tools/dspic30_sim/cpu.hpp"

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace aseba::dspic30
{

// A memory file that cannot be read (missing parts, a bad checksum) or
// written.
class MemoryFileError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

struct NonVolatileMemory {
    std::vector<uint32_t> flash;  // flash_words, 24 bits each
    std::vector<uint16_t> eeprom; // eeprom_words
    std::array<uint16_t, config_words> config{};
};

// What `memory` holds now.
NonVolatileMemory capture_memory(const ProgramMemory &memory);
// Programs every word of `contents` into `cpu` (before its reset).
void restore_memory(Cpu &cpu, const NonVolatileMemory &contents);

// Reads a memory file; throws MemoryFileError naming what is wrong.
NonVolatileMemory read_memory_file(const std::string &path);
// Writes `contents` to `path` atomically; throws MemoryFileError.
void write_memory_file(const std::string &path, const NonVolatileMemory &contents);

} // namespace aseba::dspic30
