// Target strings, and TCP and serial links over asio (byte_stream.hpp).

#include "transport.hpp"

#include <cerrno>
#include <cstdlib>
#include <fcntl.h>
#include <vector>

#include "byte_stream.hpp"

namespace aseba::client
{

namespace
{

uint16_t parse_port(const std::string &text, const std::string &target)
{
    char *end = nullptr;
    errno = 0;
    unsigned long port = std::strtoul(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0 || port == 0 || port > 65535)
        throw TransportError("target '" + target + "': port '" + text +
                             "' is not a number from 1 to 65535");
    return uint16_t(port);
}

unsigned parse_baud(const std::string &text, const std::string &target)
{
    char *end = nullptr;
    unsigned long baud = std::strtoul(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || baud == 0)
        throw TransportError("target '" + target + "': baud rate '" + text + "' is not a number");
    return unsigned(baud);
}

std::vector<std::string> split(const std::string &text, char separator)
{
    std::vector<std::string> parts;
    size_t begin = 0;
    while (true) {
        size_t end = text.find(separator, begin);
        parts.push_back(text.substr(begin, end - begin));
        if (end == std::string::npos)
            return parts;
        begin = end + 1;
    }
}

// Dashel's "key=value;key=value" parameters, or positional values in the
// order `positional_keys` gives.
void parse_parameters(const std::string &text,
                      const std::vector<std::string> &positional_keys,
                      const std::string &target,
                      TargetAddress &address)
{
    std::vector<std::string> parts = split(text, ';');
    for (size_t i = 0; i < parts.size(); i++) {
        std::string key, value;
        size_t equals = parts[i].find('=');
        if (equals == std::string::npos) {
            if (i >= positional_keys.size())
                throw TransportError("target '" + target + "': unexpected '" + parts[i] + "'");
            key = positional_keys[i];
            value = parts[i];
        } else {
            key = parts[i].substr(0, equals);
            value = parts[i].substr(equals + 1);
        }
        if (key == "host" && address.kind == TargetAddress::Kind::tcp)
            address.host = value;
        else if (key == "port" && address.kind == TargetAddress::Kind::tcp)
            address.port = parse_port(value, target);
        else if (key == "device" && address.kind == TargetAddress::Kind::serial)
            address.device = value;
        else if (key == "baud" && address.kind == TargetAddress::Kind::serial)
            address.baud = parse_baud(value, target);
        else
            throw TransportError("target '" + target + "': unknown parameter '" + key + "'");
    }
}

// A link opened and written through asio, read without waiting (the
// caller polls fd()).
class AsioTransport : public Transport
{
  public:
    AsioTransport(const TargetAddress &address, int timeout_ms)
      : name_(target_text(address))
    {
        stream_.open(address, std::chrono::milliseconds(timeout_ms));
        fd_ = stream_.native_handle();
        // Reads are ::read on the descriptor: it must not block.
        fcntl(fd_, F_SETFL, fcntl(fd_, F_GETFL) | O_NONBLOCK);
    }
    int fd() const override
    {
        return fd_;
    }
    std::string name() const override
    {
        return name_;
    }

    size_t read(uint8_t *buffer, size_t capacity) override
    {
        std::error_code error;
        size_t count = stream_.read_some(asio::buffer(buffer, capacity), error);
        if (error == asio::error::would_block)
            return 0;
        if (error == asio::error::eof)
            throw TransportError(name_ + ": the connection was closed");
        if (error)
            throw TransportError(name_ + ": read failed: " + error.message());
        return count;
    }

    void write(const uint8_t *bytes, size_t count, int timeout_ms) override
    {
        stream_.write_all(bytes, count, std::chrono::milliseconds(timeout_ms), name_);
    }

  private:
    asio::io_context io_;
    detail::ByteStream stream_{ io_ };
    std::string name_;
    int fd_ = -1;
};

} // namespace

TargetAddress parse_target(const std::string &text)
{
    TargetAddress address;
    const std::string tcp_prefix = "tcp:";
    const std::string serial_prefix = "ser:";
    if (text.rfind(tcp_prefix, 0) == 0) {
        parse_parameters(text.substr(tcp_prefix.size()), { "host", "port" }, text, address);
    } else if (text.rfind(serial_prefix, 0) == 0) {
        address.kind = TargetAddress::Kind::serial;
        parse_parameters(text.substr(serial_prefix.size()), { "device" }, text, address);
        if (address.device.empty())
            throw TransportError("target '" + text + "': no device (ser:device=PATH)");
    } else if (!text.empty() && text[0] == '/') {
        address.kind = TargetAddress::Kind::serial;
        address.device = text;
    } else if (size_t colon = text.rfind(':'); colon != std::string::npos && colon > 0) {
        address.host = text.substr(0, colon);
        address.port = parse_port(text.substr(colon + 1), text);
    } else {
        throw TransportError("target '" + text +
                             "' is none of tcp:HOST;PORT, HOST:PORT, ser:device=PATH or a "
                             "device path");
    }
    if (address.kind == TargetAddress::Kind::tcp && address.host.empty())
        throw TransportError("target '" + text + "': no host");
    return address;
}

std::string target_text(const TargetAddress &address)
{
    if (address.kind == TargetAddress::Kind::tcp)
        return "tcp:" + address.host + ";" + std::to_string(address.port);
    std::string text = "ser:device=" + address.device;
    if (address.baud != DEFAULT_SERIAL_BAUD)
        text += ";baud=" + std::to_string(address.baud);
    return text;
}

std::unique_ptr<Transport> open_transport(const TargetAddress &address, int timeout_ms)
{
    return std::make_unique<AsioTransport>(address, timeout_ms);
}

} // namespace aseba::client
