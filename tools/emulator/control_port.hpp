// A line-based control port on loopback: each line a client sends is handed
// to a handler, whose answer goes back to that client as one line. A client
// whose line is an HTTP request line (a browser, sent by a web page) is let
// go at once. Polled
// from the simulation's loop (standalone asio), it never waits, so commands
// take effect between simulation steps. Used by epuck-emu --control
// (docs/arena-format.md, "Run-time control").

#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "tools/connections/port_limit.hpp"

namespace aseba::arena
{

class ControlPort
{
  public:
    // The answer to one command line (without its line end).
    using Handler = std::function<std::string(const std::string &line)>;

    // Longest command line taken; a longer one is answered with an error
    // and the client is let go, so that no client holds memory unbounded.
    static constexpr size_t longest_line = 1024;
    // Clients at once (tools/connections/port_limit.hpp).
    static constexpr size_t most_clients = 8;

    // Listens on 127.0.0.1 `port` (0: a free port, see port()); throws
    // std::runtime_error when the port cannot be opened.
    ControlPort(uint16_t port,
                Handler handler,
                const connections::PortLimit &limit = { most_clients, connections::IDLE_GRACE });
    ~ControlPort();
    ControlPort(const ControlPort &) = delete;
    ControlPort &operator=(const ControlPort &) = delete;

    uint16_t port() const;

    // Accepts clients, runs the commands of the lines they completed and
    // sends the answers, without waiting.
    void service();

    size_t client_count() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation_;
};

} // namespace aseba::arena
