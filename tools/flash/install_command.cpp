// `epuck-image install`: reads the factory HEX file, builds the Tiny
// Bootloader's packets (tiny_bootloader.hpp) and sends them over the serial
// device (tiny_upload.hpp, tiny_serial_link.hpp), telling the user what to
// do and how far it got.

#include "tools/flash/install_command.hpp"

#include <cstdio>
#include <memory>

#include "tools/command_line/command_line.hpp"
#include "tools/flash/tiny_serial_link.hpp"

extern "C" {
#include "bootloader/boot_application.h"
}

namespace aseba::flash
{

namespace
{

const char *const usage =
  "usage: epuck-image install --port DEVICE [--id N] [--wait SECONDS] FACTORY.hex";

const char *const details =
  R"(Installs FACTORY.hex (epuck-aseba-factory.hex: the Aseba bootloader, the
application and its descriptor) through the e-puck's factory Tiny
Bootloader, which listens for about 1 s after the robot's reset. Start the
command, then press the robot's reset button when it asks.

The command sends 0xC1 every 0.25 s until the Tiny Bootloader answers, then
every row from PC 0 up to the image's last one (instructions the file lacks
are written erased, 0xFFFFFF), each acknowledged 'K' (after an 'N', a bad
checksum, the row is sent again up to 3 times), then the row at 0x017F00,
then the end marker (LED6 lights for about 2 s). As the factory uploaders
do, row 0 gets GOTO 0x017F40 (the Tiny Bootloader) as its reset vector, and
the Tiny Bootloader's exit at 0x017F38 gets a GOTO to the image's own reset
target. Configuration words and EEPROM data in the file are not written.)";

const char *const exit_statuses =
  R"(Exit status: 0 when every row was acknowledged, 1 when the installation
failed (install again: once row 0 is written, every reset enters the Tiny
Bootloader), 2 on bad usage or a FACTORY.hex that cannot be read or used.)";

constexpr double default_wait_seconds = 30.0;
constexpr double longest_wait_seconds = 3600.0;
constexpr double milliseconds_per_second = 1000.0;
constexpr unsigned highest_robot_id = 0xFFFF;
constexpr std::size_t progress_steps = 10; // progress lines per installation

struct InstallOptions {
    std::string port;
    uint16_t robot_id = 0;
    double wait_seconds = default_wait_seconds;
    std::string file;
};

// A FACTORY.hex that cannot be read or used: exit status 2.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string hex(uint32_t value)
{
    char text[16];
    std::snprintf(text, sizeof text, "0x%06X", static_cast<unsigned>(value));
    return text;
}

// The command's parser, filling `options`.
std::unique_ptr<CLI::App> make_parser(InstallOptions &options)
{
    auto app = std::make_unique<CLI::App>(details, "epuck-image install");
    auto formatter = command_line::use_common_style(*app);
    formatter->set_usage(app.get(), usage);
    app->footer(exit_statuses);
    app
      ->add_option("--port",
                   options.port,
                   "the robot's serial device, such as /dev/rfcomm0 (Bluetooth) or a\n"
                   "serial adapter's tty; opened at 115200 baud, raw 8N1")
      ->required()
      ->type_name("DEVICE");
    app
      ->add_option("--id",
                   options.robot_id,
                   "the robot number (0-65535) written at 0x017F36, in the Tiny\n"
                   "Bootloader's first row; that row is rewritten at every\n"
                   "installation, so give the robot's number to keep it (default 0)")
      ->check(CLI::Range(0u, highest_robot_id).description(""))
      ->type_name("N");
    app
      ->add_option("--wait",
                   options.wait_seconds,
                   "how long to wait for the reset, more than 0 and at most 3600\n"
                   "(default 30)")
      ->check(CLI::Range(0.001, longest_wait_seconds).description(""))
      ->type_name("SECONDS");
    app->add_option("FACTORY.hex", options.file, "the factory image")->required()->type_name("");
    return app;
}

// The target of the image's reset GOTO (PC 0 and 2).
uint32_t reset_target(const ProgramImage &image)
{
    auto at = [&](uint32_t pc) {
        auto found = image.instructions.find(pc);
        return found == image.instructions.end() ? erased_instruction : found->second;
    };
    return (at(0) & 0xFFFFu) | (at(2) & BOOT_GOTO_HIGH_MASK) << 16;
}

int install(const InstallOptions &options, std::ostream &out)
{
    ProgramImage image;
    std::vector<TinyPacket> packets;
    try {
        image = read_microchip_hex_file(options.file, tiny_bootloader_base);
        packets = tiny_bootloader_packets(image, options.robot_id);
    } catch (const HexError &error) {
        std::string where = error.what();
        if (where.rfind(options.file, 0) != 0)
            where = options.file + ": " + where;
        throw InputError(where + " (the factory image is epuck-aseba-factory.hex)");
    }
    uint32_t target = reset_target(image);
    if (target >= tiny_bootloader_base)
        throw InputError(options.file + ": its reset GOTO leads to " + hex(target) +
                         ", into the Tiny Bootloader itself, not to an image of ours");

    auto link = open_tiny_serial_link(options.port);
    TinyUploadSettings settings;
    settings.handshake_timeout =
      std::chrono::milliseconds(static_cast<long>(options.wait_seconds * milliseconds_per_second));
    TinyUploadEvents events;
    events.waiting_for_reset = [&] {
        out << "Waiting for the Tiny Bootloader on " << options.port << ": press the robot's "
            << "reset button now (giving up after " << options.wait_seconds << " s)." << std::endl;
    };
    events.connected = [&] {
        out << "The Tiny Bootloader answered; writing " << packets.size() << " rows." << std::endl;
    };
    events.resending = [&](std::size_t packet, unsigned attempt) {
        out << "Row " << packet + 1 << " (PC " << hex(tiny_packet_address(packets[packet]))
            << ") had a bad checksum ('N'): sending it again (" << attempt << ")." << std::endl;
    };
    events.row_written = [&](std::size_t written, std::size_t total) {
        if (written * progress_steps / total != (written - 1) * progress_steps / total)
            out << "rows " << written << "/" << total << std::endl;
    };
    auto started = std::chrono::steady_clock::now();
    TinyUploadSummary summary = tiny_upload(*link, packets, settings, events);
    char seconds[32];
    std::snprintf(
      seconds,
      sizeof seconds,
      "%.1f",
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());

    uint32_t last_row = tiny_packet_address(packets[packets.size() - 2]);
    out << "Installed " << options.file << ": " << summary.rows << " rows (PC 0x000000-"
        << hex(last_row + page_span - 1) << ", then " << hex(tiny_bootloader_base) << ") in "
        << seconds << " s, " << summary.resends << " sent again; robot number " << options.robot_id
        << ".\n"
        << "At every reset: the Tiny Bootloader (about 1 s), then GOTO " << hex(target)
        << ", the image's reset target.\n";
    if (image.skipped_bytes > 0)
        out << "Skipped " << image.skipped_bytes << " bytes of configuration words and EEPROM "
            << "data (the Tiny Bootloader writes program flash only).\n";
    return 0;
}

} // namespace

int run_install_command(const std::vector<std::string> &arguments,
                        std::ostream &out,
                        std::ostream &err)
{
    InstallOptions options;
    std::unique_ptr<CLI::App> parser = make_parser(options);
    try {
        // CLI11 takes the arguments last first.
        std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());
        parser->parse(reversed);
    } catch (const CLI::CallForHelp &) {
        out << parser->help();
        return command_line::EXIT_OK;
    } catch (const CLI::ParseError &error) {
        err << "epuck-image install: " << error.what()
            << "\n(epuck-image install --help for usage)\n";
        return command_line::EXIT_USAGE;
    }
    try {
        return install(options, out);
    } catch (const InputError &error) {
        err << "epuck-image install: " << error.what() << "\n";
        return command_line::EXIT_USAGE;
    } catch (const std::exception &error) {
        err << "epuck-image install: " << error.what() << "\n";
        return command_line::EXIT_FAILED;
    }
}

} // namespace aseba::flash
