// What a simulated e-puck's memories hold before it powers on: the
// application image the bootloader checks after a reset, the user's program
// in the bytecode store, and memories kept in files between runs.

#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tools/flash/hex_image.hpp"

extern "C" {
#include "ports/host/host_robot.h"
}

namespace aseba::host
{

// The image a simulated robot leaves the factory with: one instruction that
// loops on itself at the start of the application region, and the
// descriptor that makes the bootloader accept it. The host runs this build's
// firmware in place of whatever valid image the flash holds.
flash::ProgramImage placeholder_application();

// Reads a Microchip HEX file of an application image (with its descriptor,
// as the bootloader receives it); throws std::runtime_error naming the file
// and the fault.
flash::ProgramImage read_application_file(const std::string &path);

// Writes `image` into the board's flash row by row, as a programmer would.
// Throws std::runtime_error when a row does not take.
void install_application(hal_board &board, const flash::ProgramImage &image);

// Stores `bytecode` in the board's bytecode store, as WRITE_BYTECODE does,
// so that the firmware starts it at boot. Throws when it does not fit.
void store_program(hal_board &board, const std::vector<uint16_t> &bytecode);

// Loads the memories saved at `path`; false when there is no such file.
// Throws when the file exists but is not a robot's memories.
bool load_memories(hal_board &board, const std::string &path);

// A robot's flash and EEPROM kept in a file as they change, so that they
// outlive the process whatever way it ends (kill -9 included), as a chip's
// outlive a power cut. The file has host_board_save_memory's layout.
class MemoryFile
{
  public:
    // Opens (or creates) `path` and writes the board's memories into it
    // whole. Throws std::runtime_error naming the file.
    MemoryFile(const hal_board &board, std::string path);
    ~MemoryFile();
    MemoryFile(const MemoryFile &) = delete;
    MemoryFile &operator=(const MemoryFile &) = delete;

    // Writes the rows and words that changed since the last call, if the
    // board erased or wrote anything since; cheap when it did not. Throws
    // std::runtime_error when the file cannot be written.
    void sync();

  private:
    void write_at(size_t offset, const uint8_t *bytes, size_t count);
    const hal_board &board_;
    std::string path_;
    int fd_ = -1;
    uint32_t operations_seen_ = 0;
    // The memories as the file holds them.
    std::vector<uint16_t> eeprom_;
    std::vector<uint32_t> flash_;
};

// Powers a robot on: its flash gets the placeholder application, then
// `prepare` (if given) may change its memories, then `bytecode` (if not
// empty) is stored, and its bootloader decides (host_robot_power_on): the
// firmware starts with the stored program, or, when the flash no longer
// holds a valid application, the robot waits in its bootloader.
void power_on(host_robot &robot,
              const std::function<void(host_robot &)> &prepare,
              const std::vector<uint16_t> &bytecode);

} // namespace aseba::host
