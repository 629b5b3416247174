// The Tiny Bootloader's upload protocol (fact sheet §4.2), over a TinyLink.

#include "tools/flash/tiny_upload.hpp"

#include <cstdio>
#include <string>

namespace aseba::flash
{
namespace
{

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

constexpr unsigned bits_per_byte = 8;

std::string hex(uint32_t value, int digits)
{
    char text[16];
    std::snprintf(text, sizeof text, "0x%0*X", digits, static_cast<unsigned>(value));
    return text;
}

milliseconds time_left(Clock::time_point deadline)
{
    auto left = std::chrono::duration_cast<milliseconds>(deadline - Clock::now());
    return left.count() > 0 ? left : milliseconds(0);
}

std::string seconds_text(milliseconds duration)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.1f s", static_cast<double>(duration.count()) / 1000.0);
    return text;
}

// Sends 0xC1 until Tiny answers 'q' then 'K', or throws.
void handshake(TinyLink &link, const TinyUploadSettings &settings, const TinyUploadEvents &events)
{
    link.discard_input();
    if (events.waiting_for_reset)
        events.waiting_for_reset();
    const uint8_t hello[] = { tiny_hello };
    auto give_up = Clock::now() + settings.handshake_timeout;
    while (Clock::now() < give_up) {
        link.send(hello);
        auto next_hello = std::min(Clock::now() + settings.hello_interval, give_up);
        bool device_type_seen = false;
        while (auto byte = link.receive(time_left(next_hello))) {
            if (*byte == tiny_ok && device_type_seen) {
                if (events.connected)
                    events.connected();
                return;
            }
            device_type_seen = *byte == tiny_device_type;
            if (device_type_seen) // its 'K' follows at once: send no 0xC1 meanwhile
                next_hello = Clock::now() + settings.reply_timeout;
        }
    }
    throw TinyUploadError("no answer from the Tiny Bootloader within " +
                          seconds_text(settings.handshake_timeout) +
                          ": press the robot's reset button while this command waits, and "
                          "make sure that nothing else uses the robot's serial link");
}

std::string row_text(const std::vector<TinyPacket> &packets, std::size_t index)
{
    return "row " + std::to_string(index + 1) + "/" + std::to_string(packets.size()) + " (PC " +
           hex(tiny_packet_address(packets[index]), 6) + ")";
}

} // namespace

uint32_t tiny_packet_address(const TinyPacket &packet)
{
    return static_cast<uint32_t>(packet[0]) | static_cast<uint32_t>(packet[1]) << bits_per_byte |
           static_cast<uint32_t>(packet[2]) << (2 * bits_per_byte);
}

TinyUploadSummary tiny_upload(TinyLink &link,
                              const std::vector<TinyPacket> &packets,
                              const TinyUploadSettings &settings,
                              const TinyUploadEvents &events)
{
    handshake(link, settings, events);
    TinyUploadSummary summary;
    for (std::size_t index = 0; index < packets.size(); index++) {
        for (unsigned attempt = 0;; attempt++) {
            link.send(packets[index]);
            summary.bytes_sent += packets[index].size();
            auto reply = link.receive(settings.reply_timeout);
            if (!reply)
                throw TinyUploadError(
                  "no reply to " + row_text(packets, index) + " within " +
                  seconds_text(settings.reply_timeout) +
                  ": the robot stopped answering (battery, Bluetooth link?). The reset vector "
                  "still leads to the Tiny Bootloader once row 0 is written: install again");
            if (*reply == tiny_ok)
                break;
            if (*reply != tiny_bad_checksum)
                throw TinyUploadError("unexpected reply " + hex(*reply, 2) + " to " +
                                      row_text(packets, index) + " (expected 'K' or 'N')");
            if (attempt == settings.resends)
                throw TinyUploadError(row_text(packets, index) + " arrived with a bad checksum " +
                                      std::to_string(attempt + 1) +
                                      " times ('N'): the link corrupts bytes; install again");
            summary.resends++;
            if (events.resending)
                events.resending(index, attempt + 1);
        }
        summary.rows++;
        if (events.row_written)
            events.row_written(summary.rows, packets.size());
    }
    auto end = tiny_bootloader_end(settings.led_ticks);
    link.send(end);
    summary.bytes_sent += end.size();
    link.finish_sending();
    return summary;
}

} // namespace aseba::flash
