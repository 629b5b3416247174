// `epuck-image install`: reads the factory HEX file, builds the Tiny
// Bootloader's packets (tiny_bootloader.hpp) and sends them over the serial
// device (tiny_upload.hpp, tiny_serial_link.hpp), telling the user what to
// do and how far it got.

#include "tools/flash/install_command.hpp"

#include <cstdio>

#include "tools/flash/tiny_serial_link.hpp"

extern "C" {
#include "bootloader/boot_application.h"
}

namespace aseba::flash
{

const char *const install_usage =
  R"(usage: epuck-image install --port DEVICE [--id N] [--wait SECONDS] FACTORY.hex

Installs FACTORY.hex (epuck-aseba-factory.hex: the Aseba bootloader, the
application and its descriptor) through the e-puck's factory Tiny
Bootloader, which listens for about 1 s after the robot's reset. Start the
command, then press the robot's reset button when it asks.

  --port DEVICE   the robot's serial device, such as /dev/rfcomm0 (Bluetooth)
                  or a serial adapter's tty; opened at 115200 baud, raw 8N1
  --id N          the robot number (0-65535) written at 0x017F36, in the Tiny
                  Bootloader's first row; that row is rewritten at every
                  installation, so give the robot's number to keep it
                  (default 0)
  --wait SECONDS  how long to wait for the reset (default 30)
  --help          show this text

The command sends 0xC1 every 0.25 s until the Tiny Bootloader answers, then
every row from PC 0 up to the image's last one (instructions the file lacks
are written erased, 0xFFFFFF), each acknowledged 'K' (after an 'N', a bad
checksum, the row is sent again up to 3 times), then the row at 0x017F00,
then the end marker (LED6 lights for about 2 s). As the factory uploaders
do, row 0 gets GOTO 0x017F40 (the Tiny Bootloader) as its reset vector, and
the Tiny Bootloader's exit at 0x017F38 gets a GOTO to the image's own reset
target. Configuration words and EEPROM data in the file are not written.

Exit status: 0 when every row was acknowledged, 1 when the installation
failed (install again: once row 0 is written, every reset enters the Tiny
Bootloader), 2 for a usage error.
)";

namespace
{

constexpr double default_wait_seconds = 30.0;
constexpr double longest_wait_seconds = 3600.0;
constexpr double milliseconds_per_second = 1000.0;
constexpr unsigned long highest_robot_id = 0xFFFF;
constexpr std::size_t progress_steps = 10; // progress lines per installation

struct InstallOptions {
    std::string port;
    uint16_t robot_id = 0;
    double wait_seconds = default_wait_seconds;
    std::string file;
};

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string hex(uint32_t value)
{
    char text[16];
    std::snprintf(text, sizeof text, "0x%06X", static_cast<unsigned>(value));
    return text;
}

uint16_t parse_robot_id(const std::string &text)
{
    std::size_t used = 0;
    unsigned long value = 0;
    try {
        value = std::stoul(text, &used, 0);
    } catch (const std::exception &) {
        used = 0;
    }
    if (used != text.size() || text.empty() || text[0] == '-' || value > highest_robot_id)
        throw UsageError("--id takes a number from 0 to 65535, not '" + text + "'");
    return static_cast<uint16_t>(value);
}

double parse_wait(const std::string &text)
{
    std::size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception &) {
        used = 0;
    }
    if (used != text.size() || !(value > 0) || value > longest_wait_seconds)
        throw UsageError("--wait takes seconds, more than 0 and at most 3600, not '" + text + "'");
    return value;
}

InstallOptions parse_options(const std::vector<std::string> &arguments)
{
    InstallOptions options;
    bool port_given = false;
    for (std::size_t i = 0; i < arguments.size(); i++) {
        const std::string &argument = arguments[i];
        bool takes_value = argument == "--port" || argument == "--id" || argument == "--wait";
        if (takes_value && i + 1 == arguments.size())
            throw UsageError(argument + " needs a value");
        if (argument == "--port") {
            options.port = arguments[++i];
            port_given = true;
        } else if (argument == "--id") {
            options.robot_id = parse_robot_id(arguments[++i]);
        } else if (argument == "--wait") {
            options.wait_seconds = parse_wait(arguments[++i]);
        } else if (argument.rfind("-", 0) == 0) {
            throw UsageError("unknown option '" + argument + "'");
        } else if (!options.file.empty()) {
            throw UsageError("one FACTORY.hex only ('" + options.file + "', then '" + argument +
                             "')");
        } else {
            options.file = argument;
        }
    }
    if (!port_given || options.port.empty())
        throw UsageError("--port DEVICE is required");
    if (options.file.empty())
        throw UsageError("FACTORY.hex is missing");
    return options;
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
        throw std::runtime_error(where + " (the factory image is epuck-aseba-factory.hex)");
    }
    uint32_t target = reset_target(image);
    if (target >= tiny_bootloader_base)
        throw std::runtime_error(options.file + ": its reset GOTO leads to " + hex(target) +
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
    for (const std::string &argument : arguments) {
        if (argument == "--help") {
            out << install_usage;
            return 0;
        }
    }
    try {
        return install(parse_options(arguments), out);
    } catch (const UsageError &error) {
        err << "epuck-image install: " << error.what() << "\n\n" << install_usage;
        return 2;
    } catch (const std::exception &error) {
        err << "epuck-image install: " << error.what() << "\n";
        return 1;
    }
}

} // namespace aseba::flash
