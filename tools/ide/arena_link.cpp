// The arena feed's client on the server's io_context.

#include "arena_link.hpp"

#include <iostream>

#include <asio/connect.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/read_until.hpp>
#include <asio/steady_timer.hpp>
#include <asio/streambuf.hpp>

namespace aseba::ide
{

namespace
{

// A line longer than this is no arena feed: the link is dropped.
constexpr size_t MAX_LINE_BYTES = 1024 * 1024;

} // namespace

// Shared with the handlers in flight, which may outlive the ArenaLink.
struct ArenaLink::Implementation : std::enable_shared_from_this<Implementation> {
    Implementation(asio::io_context &io_context,
                   std::string host_name,
                   uint16_t port_number,
                   ArenaReports reports)
      : io(io_context)
      , host(std::move(host_name))
      , port(port_number)
      , report(std::move(reports))
      , socket(io_context)
      , resolver(io_context)
      , timer(io_context)
      , input(MAX_LINE_BYTES)
    {
    }

    asio::io_context &io;
    const std::string host;
    const uint16_t port;
    const ArenaReports report;
    asio::ip::tcp::socket socket;
    asio::ip::tcp::resolver resolver;
    asio::steady_timer timer;
    asio::streambuf input;
    bool connected = false;
    bool stopped = false;

    void connect()
    {
        auto self = shared_from_this();
        resolver.async_resolve(
          host, std::to_string(port), [self](const std::error_code &error, auto endpoints) {
              if (self->stopped)
                  return;
              if (error)
                  return self->retry();
              asio::async_connect(self->socket,
                                  endpoints,
                                  [self](const std::error_code &connect_error, const auto &) {
                                      if (self->stopped)
                                          return;
                                      if (connect_error)
                                          return self->retry();
                                      self->connected = true;
                                      self->read();
                                  });
          });
    }

    void read()
    {
        auto self = shared_from_this();
        asio::async_read_until(
          socket, input, '\n', [self](const std::error_code &error, size_t length) {
              if (self->stopped)
                  return;
              if (error)
                  return self->retry();
              std::string line(asio::buffers_begin(self->input.data()),
                               asio::buffers_begin(self->input.data()) + std::ptrdiff_t(length));
              self->input.consume(length);
              nlohmann::json message = nlohmann::json::parse(line, nullptr, false);
              if (message.is_object() && message.value("type", "") == "arena" &&
                  message.contains("arena"))
                  self->report.arena(std::move(message["arena"]));
              else if (message.is_object() && message.value("type", "") == "state")
                  self->report.state(std::move(message));
              self->read();
          });
    }

    void retry()
    {
        std::error_code ignored;
        socket.close(ignored);
        input.consume(input.size());
        if (connected)
            report.gone();
        connected = false;
        auto self = shared_from_this();
        timer.expires_after(RETRY_PERIOD);
        timer.async_wait([self](const std::error_code &error) {
            if (!error && !self->stopped)
                self->connect();
        });
    }
};

ArenaLink::ArenaLink(asio::io_context &io, std::string host, uint16_t port, ArenaReports reports)
  : implementation_(std::make_shared<Implementation>(io, std::move(host), port, std::move(reports)))
{
    implementation_->connect();
}

ArenaLink::~ArenaLink()
{
    implementation_->stopped = true;
    std::error_code ignored;
    implementation_->socket.close(ignored);
    implementation_->resolver.cancel();
    implementation_->timer.cancel();
}

} // namespace aseba::ide
