// Installing an image through the e-puck's factory Tiny Bootloader
// (hardware fact sheet §4.2): the 0xC1 handshake while the user resets the
// robot, the row packets of tiny_bootloader.hpp each answered 'K' (or 'N',
// then sent again), and the end marker. The protocol runs over any TinyLink,
// so tests can drive it without a serial port (tiny_serial_link.hpp is the
// serial one).

#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "tools/flash/tiny_bootloader.hpp"

namespace aseba::flash
{

// Why an installation stopped; what() says what happened and what to do.
struct TinyUploadError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A byte link to the robot's UART1.
class TinyLink
{
  public:
    virtual ~TinyLink() = default;
    // Sends every byte of `bytes`; throws std::runtime_error when the link fails.
    virtual void send(std::span<const uint8_t> bytes) = 0;
    // The next byte received within `timeout`, or nothing.
    virtual std::optional<uint8_t> receive(std::chrono::milliseconds timeout) = 0;
    // Drops the bytes received and not read yet.
    virtual void discard_input() = 0;
    // Returns once every byte sent has left the computer.
    virtual void finish_sending() = 0;
};

// The bytes of the protocol (fact sheet §4.2).
inline constexpr uint8_t tiny_hello = 0xC1;       // the host's "are you there"
inline constexpr uint8_t tiny_device_type = 0x71; // 'q': the dsPIC30F6014A, before the first 'K'
inline constexpr uint8_t tiny_ok = 'K';
inline constexpr uint8_t tiny_bad_checksum = 'N';

// LED6 stays on for this many ticks of about 13.4 ms at the end: about 2 s,
// as epuckuploadbt does (fact sheet §4.2 step 6).
inline constexpr uint16_t tiny_default_led_ticks = 0x95;

struct TinyUploadSettings {
    // How long to send 0xC1 while waiting for the user to reset the robot.
    std::chrono::milliseconds handshake_timeout{ 30000 };
    // The wait for an answer before the next 0xC1. Tiny listens about 1 s
    // after a reset, so this leaves several tries in that window, and time
    // for the answer to come back over Bluetooth: a 0xC1 sent after Tiny
    // answered would be taken as the first byte of the first packet.
    std::chrono::milliseconds hello_interval{ 250 };
    // The wait for a row's 'K' or 'N' (the row takes about 4 ms to erase and
    // program; Bluetooth adds its latency).
    std::chrono::milliseconds reply_timeout{ 2000 };
    // How many times a packet answered 'N' (bad checksum) is sent again.
    unsigned resends = 3;
    uint16_t led_ticks = tiny_default_led_ticks;
};

// What the installation tells its user as it goes; every one may be empty.
struct TinyUploadEvents {
    std::function<void()> waiting_for_reset;                             // sending 0xC1 from now on
    std::function<void()> connected;                                     // Tiny answered 'q' 'K'
    std::function<void(std::size_t packet, unsigned attempt)> resending; // after an 'N'
    std::function<void(std::size_t written, std::size_t total)> row_written;
};

struct TinyUploadSummary {
    std::size_t rows = 0;    // packets acknowledged
    std::size_t resends = 0; // packets sent again after an 'N'
    std::size_t bytes_sent = 0;
};

// The PC address a packet writes (its first 3 bytes).
uint32_t tiny_packet_address(const TinyPacket &packet);

// Installs `packets` (tiny_bootloader_packets) through the link: discards
// what the link has received, sends 0xC1 every hello_interval until Tiny
// answers 'q' then 'K' (other bytes, from a running firmware, are ignored),
// then each packet in order, waiting for its 'K' and sending it again after
// an 'N' up to `resends` times, then the end marker with `led_ticks`, and
// waits for the link to send it. Throws TinyUploadError when no answer comes
// within handshake_timeout, a packet gets no reply within reply_timeout, an
// 'N' once too often, or any other reply; errors of the link pass through.
TinyUploadSummary tiny_upload(TinyLink &link,
                              const std::vector<TinyPacket> &packets,
                              const TinyUploadSettings &settings,
                              const TinyUploadEvents &events = {});

} // namespace aseba::flash
