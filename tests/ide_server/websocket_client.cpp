// websocketpp's client, in a thread of its own. C++17, like the server's
// web_server.cpp, for the same reason.

#include "websocket_client.hpp"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <websocketpp/client.hpp>
#include <websocketpp/config/asio_no_tls_client.hpp>

namespace ide_test
{

using Client = websocketpp::client<websocketpp::config::asio_client>;

struct WebSocketClient::Implementation {
    Client client;
    websocketpp::connection_hdl handle;
    std::thread thread;
    std::mutex mutex;
    std::condition_variable changed;
    std::deque<std::string> received;
    bool open = false;
    bool closed = false;
    std::string failure;
};

WebSocketClient::WebSocketClient(const std::string &url, const std::string &origin)
  : implementation_(std::make_unique<Implementation>())
{
    Implementation &self = *implementation_;
    self.client.clear_access_channels(websocketpp::log::alevel::all);
    self.client.clear_error_channels(websocketpp::log::elevel::all);
    self.client.init_asio();
    self.client.set_open_handler([&self](websocketpp::connection_hdl) {
        std::lock_guard lock(self.mutex);
        self.open = true;
        self.changed.notify_all();
    });
    auto ended = [&self](websocketpp::connection_hdl handle) {
        std::lock_guard lock(self.mutex);
        websocketpp::lib::error_code ignored;
        if (auto connection = self.client.get_con_from_hdl(handle, ignored);
            connection && !self.open)
            self.failure = "refused: HTTP " + std::to_string(connection->get_response_code()) +
                           " " + connection->get_ec().message();
        self.closed = true;
        self.changed.notify_all();
    };
    self.client.set_close_handler(ended);
    self.client.set_fail_handler(ended);
    self.client.set_message_handler(
      [&self](websocketpp::connection_hdl, Client::message_ptr message) {
          std::lock_guard lock(self.mutex);
          self.received.push_back(message->get_payload());
          self.changed.notify_all();
      });
    websocketpp::lib::error_code error;
    Client::connection_ptr connection = self.client.get_connection(url, error);
    if (error)
        throw std::runtime_error("cannot connect to " + url + ": " + error.message());
    if (!origin.empty())
        connection->append_header("Origin", origin);
    self.handle = connection->get_handle();
    self.client.connect(connection);
    self.thread = std::thread([&self] { self.client.run(); });
    std::unique_lock lock(self.mutex);
    self.changed.wait_for(
      lock, std::chrono::seconds(5), [&self] { return self.open || self.closed; });
    if (!self.open) {
        lock.unlock();
        std::string why = self.failure.empty() ? "no answer" : self.failure;
        self.client.stop();
        self.thread.join();
        throw std::runtime_error("WebSocket " + url + " " + why);
    }
}

WebSocketClient::~WebSocketClient()
{
    Implementation &self = *implementation_;
    websocketpp::lib::error_code ignored;
    self.client.close(self.handle, websocketpp::close::status::normal, "", ignored);
    self.client.stop();
    self.thread.join();
}

void WebSocketClient::send(const std::string &text)
{
    websocketpp::lib::error_code error;
    implementation_->client.send(
      implementation_->handle, text, websocketpp::frame::opcode::text, error);
    if (error)
        throw std::runtime_error("cannot send: " + error.message());
}

std::optional<std::string> WebSocketClient::receive(std::chrono::milliseconds limit)
{
    Implementation &self = *implementation_;
    std::unique_lock lock(self.mutex);
    self.changed.wait_for(lock, limit, [&self] { return !self.received.empty() || self.closed; });
    if (self.received.empty())
        return std::nullopt;
    std::string message = std::move(self.received.front());
    self.received.pop_front();
    return message;
}

bool WebSocketClient::closed() const
{
    std::lock_guard lock(implementation_->mutex);
    return implementation_->closed;
}

} // namespace ide_test
