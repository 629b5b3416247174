// The toolchain's folder comes from the build (PIC30_BIN, tests/dspic30_sim/module.mk).

#include "tests/dspic30_sim/pic30_toolchain.hpp"

#include "tools/dspic30_sim/intel_hex.hpp"

#include <array>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

namespace aseba::dspic30::test
{

std::string pic30_tool(const std::string &name)
{
    return std::string(PIC30_BIN) + "/pic30-elf-" + name;
}

std::string run_command(const std::string &command)
{
    FILE *pipe = popen(command.c_str(), "r");
    if (!pipe)
        throw std::runtime_error("cannot run: " + command);
    std::string output;
    std::array<char, 65536> buffer;
    std::size_t n;
    while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
        output.append(buffer.data(), n);
    const int status = pclose(pipe);
    if (status != 0)
        throw std::runtime_error("command failed (status " + std::to_string(status) +
                                 "): " + command);
    return output;
}

ScratchFolder::ScratchFolder()
{
    std::random_device entropy;
    const auto base = std::filesystem::temp_directory_path();
    for (;;) {
        path_ =
          base / ("dspic30-sim-test-" + std::to_string(getpid()) + "-" + std::to_string(entropy()));
        if (std::filesystem::create_directory(path_))
            return;
    }
}

ScratchFolder::~ScratchFolder()
{
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

void write_text_file(const std::string &path, const std::string &text)
{
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out)
        throw std::runtime_error("cannot write " + path);
}

AssembledProgram assemble_program(const std::string &source, uint32_t base)
{
    ScratchFolder folder;
    std::ostringstream script;
    // No start-up files; RAM and EEPROM named as the linker wants them.
    script << "OUTPUT_ARCH(\"30F6014A\")\n"
           << "CRT0_STARTUP(none.o)\nCRT1_STARTUP(none.o)\nCRT_STARTMODE(crt_start_mode_off)\n"
           << "MEMORY { data (a!xr) : ORIGIN = 0x800, LENGTH = 0x2000\n"
           << "  program (xr) : ORIGIN = 0x" << std::hex << base << ", LENGTH = 0x"
           << (0x17F00 - base) << "\n  eedata : ORIGIN = 0x7FF000, LENGTH = 0x1000 }\n"
           << "SECTIONS { .text : { *(.text); } >program }\n";
    write_text_file(folder.file("program.s"), source);
    write_text_file(folder.file("program.gld"), script.str());
    run_command(pic30_tool("as") + " -p30F6014A " + folder.file("program.s") + " -o " +
                folder.file("program.o"));
    run_command(pic30_tool("ld") + " --no-isr --no-ivt -T " + folder.file("program.gld") + " " +
                folder.file("program.o") + " -o " + folder.file("program.elf") + " 2>&1");
    run_command(pic30_tool("bin2hex") + " " + folder.file("program.elf"));
    AssembledProgram program;
    program.words = read_intel_hex_file(folder.file("program.hex"));
    std::ifstream hex(folder.file("program.hex"));
    std::ostringstream text;
    text << hex.rdbuf();
    program.hex = text.str();
    std::istringstream symbols(run_command(pic30_tool("nm") + " " + folder.file("program.elf")));
    std::string line;
    while (std::getline(symbols, line)) {
        std::istringstream fields(line);
        std::string address, kind, name;
        if (fields >> address >> kind >> name)
            program.symbols[name] = static_cast<uint32_t>(std::stoul(address, nullptr, 16));
    }
    return program;
}

} // namespace aseba::dspic30::test
