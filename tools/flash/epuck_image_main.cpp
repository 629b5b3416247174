// epuck-image: the last step of `make dspic30`. Reads the application and
// bootloader HEX files that XC16 wrote, adds the application's descriptor,
// and writes the two images of tools/flash/epuck_image.hpp. With `install`
// first, it installs the factory image on a robot through the factory Tiny
// Bootloader (install_command.hpp).

#include <cstdint>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "tools/command_line/command_line.hpp"
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
       epuck-image dump IMAGE.hex)";

constexpr const char *details =
  R"(Builds the e-puck's images from the XC16 HEX files of the application
(linked with linker/epuck-app.gld) and of the Aseba bootloader (linked with
linker/epuck-bootloader.gld):

  OUTPUT.hex   the application with its descriptor (entry: the reset slot
               of its GOTO table), for the Aseba bootloader (`aseba flash`,
               asebacmd whex); every instruction of the pages it covers is
               written, erased ones as 0xFFFFFF, so that tools which fill
               missing bytes with zeros (asebacmd) write what the
               descriptor's CRC expects
  FACTORY.hex  the bootloader, the application and its descriptor, for the
               first installation through the factory Tiny Bootloader or a
               programmer

The second form installs FACTORY.hex on a robot through its factory Tiny
Bootloader (`epuck-image install --help` tells more). The third prints
every instruction and configuration word of IMAGE.hex as this program reads
it, one "ADDRESS VALUE" line each (PC addresses, hexadecimal), in address
order: what `make dspic30` compares with the linked programs.)";

void write_file(const std::string &path, const std::string &text)
{
    if (std::string error = aseba::command_line::write_whole_file(path, text); !error.empty())
        throw std::runtime_error(error);
}

struct Files {
    std::string application, bootloader, output, factory;
};

Files parse_command_line(int argc, char **argv)
{
    Files files;
    CLI::App app(details, "epuck-image");
    auto formatter = aseba::command_line::use_common_style(app);
    formatter->set_usage(&app, usage);
    app.footer(aseba::command_line::EXIT_STATUS_TEXT);
    app.add_option("APPLICATION.hex", files.application, "the application, as XC16 links it")
      ->required()
      ->type_name("");
    app.add_option("BOOTLOADER.hex", files.bootloader, "the Aseba bootloader, as XC16 links it")
      ->required()
      ->type_name("");
    app.add_option("OUTPUT.hex", files.output, "the application image to write")
      ->required()
      ->type_name("");
    app.add_option("FACTORY.hex", files.factory, "the factory image to write")
      ->required()
      ->type_name("");
    aseba::command_line::parse_or_exit(app, argc, argv);
    return files;
}

// `epuck-image dump IMAGE.hex`: the image's words as read_microchip_hex reads them.
int dump(const std::vector<std::string> &arguments)
{
    if (arguments.size() != 1) {
        std::cerr << "epuck-image: usage: epuck-image dump IMAGE.hex\n";
        return aseba::command_line::EXIT_USAGE;
    }
    aseba::flash::ProgramImage image;
    try {
        // Any address: a dump shows what is there, descriptor included.
        image = aseba::flash::read_microchip_hex_file(arguments[0], UINT32_MAX);
    } catch (const std::exception &error) {
        std::cerr << "epuck-image: " << error.what() << "\n";
        return aseba::command_line::EXIT_USAGE;
    }
    char line[32];
    auto print = [&](uint32_t address, uint32_t value) {
        std::snprintf(line, sizeof line, "0x%06X 0x%06X\n", unsigned(address), unsigned(value));
        std::cout << line;
    };
    for (const auto &[address, value] : image.instructions)
        print(address, value);
    for (const auto &[address, value] : image.configuration)
        print(address, value);
    return aseba::command_line::EXIT_OK;
}

// The program; its output is checked by main.
int build_or_install(int argc, char **argv)
{
    if (argc >= 2 && std::string(argv[1]) == "install")
        return aseba::flash::run_install_command(
          std::vector<std::string>(argv + 2, argv + argc), std::cout, std::cerr);
    if (argc >= 2 && std::string(argv[1]) == "dump")
        return dump(std::vector<std::string>(argv + 2, argv + argc));
    Files files = parse_command_line(argc, argv);
    aseba::flash::ProgramImage application, bootloader;
    try {
        application =
          aseba::flash::read_microchip_hex_file(files.application, BOOT_DESCRIPTOR_ADDRESS);
        bootloader = aseba::flash::read_microchip_hex_file(files.bootloader, BOOT_TINY_BASE);
        try {
            aseba::flash::add_application_descriptor(application);
        } catch (const aseba::flash::HexError &error) {
            throw aseba::flash::HexError(files.application + ": " + error.what());
        }
        try {
            aseba::flash::check_bootloader_image(bootloader);
        } catch (const aseba::flash::HexError &error) {
            throw aseba::flash::HexError(files.bootloader + ": " + error.what());
        }
    } catch (const std::exception &error) {
        std::cerr << "epuck-image: " << error.what() << "\n";
        return aseba::command_line::EXIT_USAGE;
    }
    try {
        // The application image carries only program flash (the Aseba
        // bootloader cannot write configuration words), every page whole.
        aseba::flash::ProgramImage flashable;
        flashable.instructions = application.instructions;
        write_file(files.output,
                   aseba::flash::write_microchip_hex(aseba::flash::fill_pages(flashable)));
        write_file(
          files.factory,
          aseba::flash::write_microchip_hex(aseba::flash::merge_images(bootloader, application)));
    } catch (const std::exception &error) {
        std::cerr << "epuck-image: " << error.what() << "\n";
        return aseba::command_line::EXIT_FAILED;
    }
    return aseba::command_line::EXIT_OK;
}

} // namespace

int main(int argc, char **argv)
{
    return aseba::command_line::finish_standard_output("epuck-image", build_or_install(argc, argv));
}
