// What the tests of host::Network on bare host boards share: tools'
// sockets on the loopback, and the robots' side of their links. Frames are
// built by hand from protocol.md §2 (length of the payload, source, type,
// payload, little endian).

#pragma once

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <cerrno>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdexcept>
#include <string>
#include <sys/socket.h>
#include <unistd.h>
#include <vector>

extern "C" {
#include "boards/epuck_host/host_board.h"
}

namespace network_test
{

using Bytes = std::vector<uint8_t>;

inline Bytes operator+(Bytes first, const Bytes &second)
{
    first.insert(first.end(), second.begin(), second.end());
    return first;
}

// A tool's connection to `address`:port, non-blocking once connected.
class ToolSocket
{
  public:
    explicit ToolSocket(uint16_t port, const char *address = "127.0.0.1")
    {
        fd_ = socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in where{};
        where.sin_family = AF_INET;
        inet_pton(AF_INET, address, &where.sin_addr);
        where.sin_port = htons(port);
        // The listener's backlog takes the connection before accept().
        if (fd_ < 0 || connect(fd_, reinterpret_cast<sockaddr *>(&where), sizeof where) != 0) {
            int error = errno;
            if (fd_ >= 0)
                close(fd_);
            throw std::runtime_error("cannot connect to " + std::string(address) + " port " +
                                     std::to_string(port) + ": " + strerror(error));
        }
        fcntl(fd_, F_SETFL, fcntl(fd_, F_GETFL) | O_NONBLOCK);
    }
    ~ToolSocket()
    {
        close(fd_);
    }
    ToolSocket(const ToolSocket &) = delete;
    ToolSocket &operator=(const ToolSocket &) = delete;

    // Sends all of `bytes` (a few frames: the socket's buffer takes them).
    void send(const Bytes &bytes)
    {
        ASSERT_EQ(write(fd_, bytes.data(), bytes.size()), ssize_t(bytes.size()));
    }
    // Sends what the socket takes now; returns how much.
    size_t send_some(const uint8_t *bytes, size_t count)
    {
        ssize_t written = write(fd_, bytes, count);
        return written > 0 ? size_t(written) : 0;
    }
    // Moves what has arrived into received(); false once the network has
    // closed the connection.
    bool collect()
    {
        while (true) {
            uint8_t buffer[4096];
            ssize_t count = read(fd_, buffer, sizeof buffer);
            if (count == 0 || (count < 0 && errno != EAGAIN && errno != EWOULDBLOCK))
                return false;
            if (count < 0)
                return true;
            received_.insert(received_.end(), buffer, buffer + count);
        }
    }
    const Bytes &received() const
    {
        return received_;
    }
    void forget_received()
    {
        received_.clear();
    }

  private:
    int fd_ = -1;
    Bytes received_;
};

// Sends `bytes` from a robot's link, as its firmware would.
inline void robot_sends(hal_board &robot, const Bytes &bytes)
{
    robot.link_output(robot.link_context, bytes.data(), uint16_t(bytes.size()));
}

// The bytes waiting on a robot's link, taken off it, as its firmware reads
// them.
inline Bytes take_received(hal_board &robot)
{
    Bytes received;
    for (uint16_t i = 0; i < robot.receive_count; i++)
        received.push_back(robot.receive[(robot.receive_start + i) % sizeof robot.receive]);
    robot.receive_start = 0;
    robot.receive_count = 0;
    return received;
}

} // namespace network_test
