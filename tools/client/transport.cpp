// TCP and serial links, over POSIX sockets and termios.

#include "transport.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>
#include <vector>

namespace aseba::client
{

namespace
{

std::string system_error(const std::string &what)
{
    return what + ": " + std::strerror(errno);
}

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

class FileTransport : public Transport
{
  public:
    FileTransport(int fd, std::string name)
      : fd_(fd)
      , name_(std::move(name))
    {
    }
    ~FileTransport() override
    {
        close(fd_);
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
        ssize_t count = ::read(fd_, buffer, capacity);
        if (count > 0)
            return size_t(count);
        if (count == 0)
            throw TransportError(name_ + ": the connection was closed");
        if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
            return 0;
        throw TransportError(system_error(name_ + ": read failed"));
    }

    void write(const uint8_t *bytes, size_t count, int timeout_ms) override
    {
        size_t sent = 0;
        while (sent < count) {
            ssize_t written = send_or_write(fd_, bytes + sent, count - sent);
            if (written > 0) {
                sent += size_t(written);
                continue;
            }
            if (written < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
                throw TransportError(system_error(name_ + ": write failed"));
            pollfd waiting{ fd_, POLLOUT, 0 };
            if (poll(&waiting, 1, timeout_ms) <= 0)
                throw TransportError(name_ + ": the link takes no data (timed out after " +
                                     std::to_string(timeout_ms) + " ms)");
        }
    }

  private:
    // Sockets get MSG_NOSIGNAL so that a closed peer is an error, not SIGPIPE.
    static ssize_t send_or_write(int fd, const uint8_t *bytes, size_t count)
    {
        ssize_t written = ::send(fd, bytes, count, MSG_NOSIGNAL);
        if (written < 0 && errno == ENOTSOCK)
            written = ::write(fd, bytes, count);
        return written;
    }

    int fd_;
    std::string name_;
};

std::unique_ptr<Transport> open_tcp(const TargetAddress &address, int timeout_ms)
{
    std::string name = target_text(address);
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo *found = nullptr;
    std::string port = std::to_string(address.port);
    int status = getaddrinfo(address.host.c_str(), port.c_str(), &hints, &found);
    if (status != 0)
        throw TransportError(name + ": cannot resolve '" + address.host +
                             "': " + gai_strerror(status));
    std::string failure = "no address";
    for (addrinfo *candidate = found; candidate != nullptr; candidate = candidate->ai_next) {
        int fd = socket(candidate->ai_family,
                        candidate->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC,
                        candidate->ai_protocol);
        if (fd < 0) {
            failure = std::strerror(errno);
            continue;
        }
        int connected = connect(fd, candidate->ai_addr, candidate->ai_addrlen);
        if (connected != 0 && errno == EINPROGRESS) {
            pollfd waiting{ fd, POLLOUT, 0 };
            int ready = poll(&waiting, 1, timeout_ms);
            int error = 0;
            socklen_t length = sizeof error;
            if (ready <= 0)
                error = ETIMEDOUT;
            else
                getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length);
            connected = error == 0 ? 0 : -1;
            errno = error;
        }
        if (connected == 0) {
            freeaddrinfo(found);
            int on = 1;
            setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
            return std::make_unique<FileTransport>(fd, name);
        }
        failure = std::strerror(errno);
        close(fd);
    }
    freeaddrinfo(found);
    throw TransportError(name + ": cannot connect: " + failure);
}

struct BaudRate {
    unsigned rate;
    speed_t code;
};

constexpr BaudRate baud_rates[] = {
    { 9600, B9600 },     { 19200, B19200 },   { 38400, B38400 },   { 57600, B57600 },
    { 115200, B115200 }, { 230400, B230400 }, { 460800, B460800 }, { 921600, B921600 },
};

std::unique_ptr<Transport> open_serial(const TargetAddress &address)
{
    std::string name = target_text(address);
    speed_t speed = 0;
    for (const BaudRate &entry : baud_rates)
        if (entry.rate == address.baud)
            speed = entry.code;
    if (speed == 0)
        throw TransportError(name + ": unsupported baud rate " + std::to_string(address.baud));
    int fd = open(address.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        throw TransportError(system_error(name + ": cannot open " + address.device));
    // Raw 8N1 without flow control, like Dashel's defaults (protocol.md §8.2).
    termios settings{};
    if (tcgetattr(fd, &settings) != 0) {
        std::string message = system_error(name + ": not a serial device");
        close(fd);
        throw TransportError(message);
    }
    cfmakeraw(&settings);
    settings.c_cflag &= ~tcflag_t(CSTOPB | PARENB | CRTSCTS | CSIZE);
    settings.c_cflag |= CS8 | CLOCAL | CREAD;
    settings.c_cc[VMIN] = 0;
    settings.c_cc[VTIME] = 0;
    cfsetispeed(&settings, speed);
    cfsetospeed(&settings, speed);
    if (tcsetattr(fd, TCSANOW, &settings) != 0) {
        std::string message = system_error(name + ": cannot configure the port");
        close(fd);
        throw TransportError(message);
    }
    int dtr = TIOCM_DTR;
    ioctl(fd, TIOCMBIS, &dtr); // some adapters have no modem lines: not an error
    tcflush(fd, TCIOFLUSH);
    return std::make_unique<FileTransport>(fd, name);
}

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
    if (address.kind == TargetAddress::Kind::tcp)
        return open_tcp(address, timeout_ms);
    return open_serial(address);
}

} // namespace aseba::client
