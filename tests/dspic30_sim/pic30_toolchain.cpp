// The toolchain's folder comes from the build (PIC30_BIN, tests/dspic30_sim/module.mk).

#include "tests/dspic30_sim/pic30_toolchain.hpp"

#include <array>
#include <cstdio>
#include <fstream>
#include <random>
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

} // namespace aseba::dspic30::test
