// epuck-image: the last step of `make dspic30`. Reads the application and
// bootloader HEX files that XC16 wrote, adds the application's descriptor,
// and writes the two images of tools/flash/epuck_image.hpp. With `install`
// first, it installs the factory image on a robot through the factory Tiny
// Bootloader (install_command.hpp).

#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "tools/flash/epuck_image.hpp"
#include "tools/flash/install_command.hpp"

extern "C" {
#include "bootloader/boot_application.h"
}

namespace
{

constexpr const char *usage =
  R"(usage: epuck-image APPLICATION.hex BOOTLOADER.hex OUTPUT.hex FACTORY.hex
       epuck-image install --port DEVICE [--id N] [--wait SECONDS] FACTORY.hex

Builds the e-puck's images from the XC16 HEX files of the application
(linked with linker/epuck-app.gld) and of the Aseba bootloader (linked with
linker/epuck-bootloader.gld):

  OUTPUT.hex   the application with its descriptor (entry: the reset slot
               of its GOTO table), for the Aseba bootloader (asebacmd whex)
  FACTORY.hex  the bootloader, the application and its descriptor, for the
               first installation through the factory Tiny Bootloader or a
               programmer

The second form installs FACTORY.hex on a robot through its factory Tiny
Bootloader (`epuck-image install --help` tells more).

Options:
  --help       show this text
)";

void write_file(const std::string &path, const std::string &text)
{
    std::ofstream file(path, std::ios::binary);
    file << text;
    if (!file)
        throw std::runtime_error(path + ": cannot be written");
}

aseba::flash::ProgramImage read_image(const std::string &path, uint32_t end)
{
    return aseba::flash::read_microchip_hex_file(path, end);
}

} // namespace

int main(int argc, char **argv)
{
    if (argc >= 2 && std::string(argv[1]) == "install")
        return aseba::flash::run_install_command(
          std::vector<std::string>(argv + 2, argv + argc), std::cout, std::cerr);
    for (int i = 1; i < argc; i++) {
        if (std::string(argv[i]) == "--help") {
            std::cout << usage;
            return 0;
        }
    }
    if (argc != 5) {
        std::cerr << usage;
        return 2;
    }
    try {
        auto application = read_image(argv[1], BOOT_DESCRIPTOR_ADDRESS);
        auto bootloader = read_image(argv[2], BOOT_TINY_BASE);
        try {
            aseba::flash::add_application_descriptor(application);
        } catch (const aseba::flash::HexError &error) {
            throw std::runtime_error(std::string(argv[1]) + ": " + error.what());
        }
        try {
            aseba::flash::check_bootloader_image(bootloader);
        } catch (const aseba::flash::HexError &error) {
            throw std::runtime_error(std::string(argv[2]) + ": " + error.what());
        }
        // The application image carries only program flash: the Aseba
        // bootloader cannot write configuration words.
        aseba::flash::ProgramImage flashable;
        flashable.instructions = application.instructions;
        write_file(argv[3], aseba::flash::write_microchip_hex(flashable));
        write_file(
          argv[4],
          aseba::flash::write_microchip_hex(aseba::flash::merge_images(bootloader, application)));
    } catch (const std::exception &error) {
        std::cerr << "epuck-image: " << error.what() << "\n";
        return 1;
    }
    return 0;
}
