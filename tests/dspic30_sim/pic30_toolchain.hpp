// The pic30-elf toolchain (Microchip's binutils and GCC 4.5.1 for the
// dsPIC30F) as the tests of the simulator use it: an oracle and a compiler,
// run as programs in a scratch folder.

#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace aseba::dspic30::test
{

// The path of pic30-elf-`name` (as, objdump, gcc, bin2hex...).
std::string pic30_tool(const std::string &name);

// Runs `command` through the shell; returns its standard output, or throws
// std::runtime_error with the command and its exit status when it fails.
std::string run_command(const std::string &command);

// A fresh folder, removed with everything in it at the end of its scope.
class ScratchFolder
{
  public:
    ScratchFolder();
    ~ScratchFolder();
    ScratchFolder(const ScratchFolder &) = delete;
    ScratchFolder &operator=(const ScratchFolder &) = delete;

    const std::filesystem::path &path() const
    {
        return path_;
    }
    // The path of `name` in the folder.
    std::string file(const std::string &name) const
    {
        return (path_ / name).string();
    }

  private:
    std::filesystem::path path_;
};

// Writes `text` to `path`; throws std::runtime_error if it cannot.
void write_text_file(const std::string &path, const std::string &text);

// A program assembled and linked by the pic30-elf tools: its words by PC
// address (as its Intel HEX gives them) and its symbols.
struct AssembledProgram {
    std::map<uint32_t, uint32_t> words;
    std::map<std::string, uint32_t> symbols;
    std::string hex; // the Intel HEX file pic30-elf-bin2hex wrote
};

// Assembles `source` (pic30-elf-as -p30F6014A), links its .text at PC
// `base` and any other absolute sections where they say (no start-up
// files), and reads the result back.
AssembledProgram assemble_program(const std::string &source, uint32_t base);

} // namespace aseba::dspic30::test
