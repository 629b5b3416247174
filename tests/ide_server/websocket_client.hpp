// A WebSocket client for the server's tests (websocketpp, like the server;
// this header hides it, so C++20 tests can include it).

#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>

namespace ide_test
{

class WebSocketClient
{
  public:
    // Connects to `url` (ws://HOST:PORT/PATH) with `origin` as the Origin
    // header (empty: none); throws std::runtime_error when refused.
    explicit WebSocketClient(const std::string &url, const std::string &origin = "");
    ~WebSocketClient();
    WebSocketClient(const WebSocketClient &) = delete;
    WebSocketClient &operator=(const WebSocketClient &) = delete;

    void send(const std::string &text);

    // The next message, waiting at most `limit`; nullopt on time-out or once
    // the connection is closed and every message was read.
    std::optional<std::string> receive(std::chrono::milliseconds limit);

    // Whether the server closed the connection.
    bool closed() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation_;
};

} // namespace ide_test
