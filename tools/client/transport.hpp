// The links from the console to Aseba networks: a TCP connection (to a
// switch, a simulated robot or epuck-emu) or a serial device (the e-puck's
// Bluetooth link, 115200 8N1, protocol.md §8.2). Target strings follow
// Dashel's syntax: `tcp:HOST;PORT`, `tcp:host=H;port=P`, `ser:device=PATH`,
// and the shorthands `HOST:PORT` and a device path.

#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

namespace aseba::client
{

// A target that cannot be parsed, opened, read or written.
class TransportError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

constexpr uint16_t DEFAULT_TCP_PORT = 33333;
constexpr unsigned DEFAULT_SERIAL_BAUD = 115200;
inline constexpr const char *DEFAULT_TARGET = "tcp:localhost;33333";

struct TargetAddress {
    enum class Kind { tcp, serial };
    Kind kind = Kind::tcp;
    std::string host = "localhost"; // tcp
    uint16_t port = DEFAULT_TCP_PORT;
    std::string device; // serial
    unsigned baud = DEFAULT_SERIAL_BAUD;
};

// Parses a target string; throws TransportError naming what is wrong.
TargetAddress parse_target(const std::string &text);

// The canonical Dashel form of `address` (e.g. "tcp:localhost;33333").
std::string target_text(const TargetAddress &address);

// An open byte stream (a TCP socket or a serial port, over asio), for
// callers that poll a file descriptor themselves; the Network has its own
// links. Reads never block (the caller polls fd()); writes send every byte
// or throw.
class Transport
{
  public:
    virtual ~Transport() = default;
    // The file descriptor to poll for input.
    virtual int fd() const = 0;
    // Reads what is available (up to `capacity`); 0 means nothing now.
    // Throws TransportError when the peer has closed or the link failed.
    virtual size_t read(uint8_t *buffer, size_t capacity) = 0;
    // Sends all `count` bytes, waiting at most `timeout_ms` for the link to
    // take them; throws TransportError otherwise.
    virtual void write(const uint8_t *bytes, size_t count, int timeout_ms) = 0;
    // The target string it was opened with.
    virtual std::string name() const = 0;
};

// Opens the link to `address`, waiting at most `timeout_ms` to connect;
// throws TransportError with the system's reason.
std::unique_ptr<Transport> open_transport(const TargetAddress &address, int timeout_ms);

} // namespace aseba::client
