// The loopback TCP server behind --uart1 tcp:PORT, on POSIX sockets and
// poll(): the simulator is one thread, which serves the link between slices
// of simulated time.

#include "tools/dspic30_sim/tcp_link.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace aseba::dspic30
{
namespace
{

// What the link holds of the client's bytes before it stops reading them
// (the UART takes about 11,500 a second at 115,200 baud; TCP's own flow
// control then holds the client back).
constexpr std::size_t receive_limit = 64 * 1024;

std::string system_error(const std::string &what)
{
    return what + ": " + std::strerror(errno);
}

void set_non_blocking(int fd)
{
    const int flags = fcntl(fd, F_GETFL, 0);
    fcntl(fd, F_SETFL, flags | O_NONBLOCK);
}

} // namespace

uint16_t parse_tcp_target(const std::string &target)
{
    const std::string prefix = "tcp:";
    if (target.rfind(prefix, 0) != 0)
        throw std::invalid_argument("not a tcp:PORT target: " + target);
    const std::string digits = target.substr(prefix.size());
    unsigned value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() ||
        value > 65535)
        throw std::invalid_argument("the port of " + target + " is not a number 0-65535");
    return static_cast<uint16_t>(value);
}

TcpLink::TcpLink(uint16_t port)
{
    listener_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (listener_ < 0)
        throw LinkError(system_error("cannot open a socket"));
    const int yes = 1;
    // A port left in TIME_WAIT by a previous run is free to take again.
    setsockopt(listener_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(port);
    if (bind(listener_, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0 ||
        listen(listener_, 1) != 0) {
        const std::string message =
          system_error("cannot listen on tcp port " + std::to_string(port) + " of 127.0.0.1");
        close(listener_);
        throw LinkError(message);
    }
    socklen_t length = sizeof address;
    getsockname(listener_, reinterpret_cast<sockaddr *>(&address), &length);
    port_ = ntohs(address.sin_port);
    set_non_blocking(listener_);
}

TcpLink::~TcpLink()
{
    drop_client();
    close(listener_);
}

int TcpLink::read_byte()
{
    if (received_.empty())
        return -1;
    const uint8_t byte = received_.front();
    received_.pop_front();
    return byte;
}

void TcpLink::write_byte(uint8_t byte)
{
    if (client_ >= 0)
        to_send_.push_back(byte);
}

void TcpLink::service(int timeout_ms)
{
    if (client_ < 0)
        accept_client();
    send_queued();
    if (timeout_ms > 0 && received_.empty()) {
        pollfd fd{ client_ >= 0 ? client_ : listener_, POLLIN, 0 };
        poll(&fd, 1, timeout_ms);
        if (client_ < 0)
            accept_client();
    }
    receive();
}

void TcpLink::accept_client()
{
    const int fd = accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0)
        return;
    // The firmware sends a byte at a time: without TCP_NODELAY, Nagle's
    // algorithm and delayed acknowledgements hold replies back some 40 ms.
    const int yes = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
    client_ = fd;
}

void TcpLink::drop_client()
{
    if (client_ >= 0)
        close(client_);
    client_ = -1;
    to_send_.clear();
}

void TcpLink::send_queued()
{
    std::size_t sent = 0;
    while (client_ >= 0 && sent < to_send_.size()) {
        const ssize_t n =
          send(client_, to_send_.data() + sent, to_send_.size() - sent, MSG_NOSIGNAL);
        if (n > 0) {
            sent += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            break; // a client that does not read loses what does not fit
        drop_client();
        return;
    }
    to_send_.clear();
}

void TcpLink::receive()
{
    uint8_t buffer[4096];
    while (client_ >= 0 && received_.size() < receive_limit) {
        const ssize_t n = recv(client_, buffer, sizeof buffer, 0);
        if (n > 0) {
            received_.insert(received_.end(), buffer, buffer + n);
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
            return;
        drop_client(); // closed by the client, or failed
    }
}

} // namespace aseba::dspic30
