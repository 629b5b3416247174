// The IDE's web front door: one TCP port that serves the page and its assets
// over HTTP and carries the WebSocket of every browser tab (one origin, so a
// lab proxy or firewall that lets the page through lets the robots through).
// Built on websocketpp over standalone asio; this header names neither
// websocketpp nor its types, so C++20 code can include it (websocketpp 0.8
// only compiles as C++17, see web_server.cpp).

#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <asio/io_context.hpp>

#include "tools/connections/port_limit.hpp"

namespace aseba::ide
{

using ConnectionId = uint64_t;

// A file of the page, served at `path` ("/" serves "/index.html").
struct StaticFile {
    std::string_view path;
    std::string_view content_type;
    std::string_view body;
};

struct WebServerOptions {
    std::string bind_address = "127.0.0.1";
    uint16_t port = 0; // 0: any free port (read it back with port())
    // The names a browser may reach the server by, besides the loopback
    // names and IP addresses (which no other site can rebind): a request
    // naming another host in its Host header is refused, so that a page of
    // another site whose name it resolves to this computer (DNS rebinding)
    // cannot drive the robots.
    std::vector<std::string> host_names;
    // When not empty, every request must carry it: as ?token=... (the
    // address printed at start, which also sets a cookie) or as that cookie.
    std::string access_token;
    // Connections (pages, their files and WebSockets) held at once, and how
    // long one must have been silent to give its place to a newcomer.
    connections::PortLimit connections{ 128, connections::IDLE_GRACE };
    // A WebSocket message larger than this closes that connection (1009).
    size_t max_message_bytes = 4 * 1024 * 1024;
    // Above this many bytes waiting for a browser, updates that can be
    // skipped are (the browser is not reading); twice this closes it.
    size_t max_buffered_bytes = 8 * 1024 * 1024;
    // The kernel's send buffer of each connection: small enough that a
    // browser that stops reading shows in max_buffered_bytes soon, rather
    // than after megabytes that the kernel keeps.
    int socket_send_buffer_bytes = 256 * 1024;
};

// What the server tells its owner; every call happens on the io_context's
// thread.
struct WebServerHandlers {
    std::function<void(ConnectionId, const std::string &peer)> opened;
    std::function<void(ConnectionId, std::string &&message)> received;
    std::function<void(ConnectionId)> closed;
};

// A port that cannot be opened (in use, no permission, bad address).
class WebServerError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// Whether `address` (an IP address) is one of this computer's loopback
// addresses, which other computers cannot reach.
bool is_loopback_address(const std::string &address);

// The name of the cookie that carries the access token of the server on
// `port` (cookies are shared by every port of a host).
std::string token_cookie_name(uint16_t port);

enum class Delivery {
    essential, // a reply or a change of state: always queued
    skippable, // a periodic update: dropped while the browser lags
};

class WebServer
{
  public:
    // Listens at once; throws WebServerError with the system's reason.
    WebServer(asio::io_context &io,
              const WebServerOptions &options,
              std::vector<StaticFile> files,
              WebServerHandlers handlers);
    ~WebServer();
    WebServer(const WebServer &) = delete;
    WebServer &operator=(const WebServer &) = delete;

    // The port actually listened on.
    uint16_t port() const;

    // Queues a text message; false when it was dropped (unknown or closing
    // connection, or a skippable update to a browser that lags).
    bool send(ConnectionId connection, const std::string &text, Delivery delivery);

    // Bytes queued for `connection` and not yet taken by the network.
    size_t buffered_bytes(ConnectionId connection) const;

    // Closes one connection with a reason the browser can show.
    void close(ConnectionId connection, const std::string &reason);

    // Stops listening and closes every connection.
    void stop();

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation_;
};

} // namespace aseba::ide
