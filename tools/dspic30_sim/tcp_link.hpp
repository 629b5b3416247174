// UART1 of dspic30-sim as a TCP server on the loopback interface (--uart1
// tcp:PORT): the simulated e-puck becomes an Aseba node that the console,
// asebamassloader or Studio reach at tcp:localhost;PORT, as they reach a
// robot's Bluetooth serial port. One client at a time: while one is
// connected, a second one's connection is completed by the system but not
// served; it is served, with what it sent meanwhile, once the first leaves
// (as QEMU's serial server does for the STM32F4 node). With no client,
// what the robot sends is lost (as on a Bluetooth link nobody holds).

#pragma once

#include <cstdint>
#include <deque>
#include <stdexcept>
#include <string>
#include <vector>

namespace aseba::dspic30
{

// A port that cannot be opened (in use, not allowed).
class LinkError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

class TcpLink
{
  public:
    // Listens on 127.0.0.1:`port` (0: a free port the system picks).
    // Throws LinkError when it cannot.
    explicit TcpLink(uint16_t port);
    ~TcpLink();
    TcpLink(const TcpLink &) = delete;
    TcpLink &operator=(const TcpLink &) = delete;

    // The port listened on.
    uint16_t port() const
    {
        return port_;
    }
    bool connected() const
    {
        return client_ >= 0;
    }

    // The next byte the client sent, or -1 when none is waiting.
    int read_byte();
    // Queues a byte for the client (dropped when there is none).
    void write_byte(uint8_t byte);

    // Accepts a client when there is none, sends what is queued, and takes
    // what the client sent; waits up to `timeout_ms` (0: not at all) for
    // something to arrive when nothing is waiting to be read.
    void service(int timeout_ms);

  private:
    void accept_client();
    void drop_client();
    void send_queued();
    void receive();

    int listener_ = -1;
    int client_ = -1;
    uint16_t port_ = 0;
    std::deque<uint8_t> received_;
    std::vector<uint8_t> to_send_;
};

// The PORT of a --uart1 target "tcp:PORT" (0-65535); throws
// std::invalid_argument for anything else.
uint16_t parse_tcp_target(const std::string &target);

} // namespace aseba::dspic30
