// websocketpp behind WebServer. This file alone is compiled as C++17: the
// headers of websocketpp 0.8.2 (Debian 12) declare constructors with
// template-ids, which C++20 rejects; nothing of them leaks into the header.

#include "web_server.hpp"

#include <iostream>
#include <map>

#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

namespace aseba::ide
{

namespace
{

using Server = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

// "http://host:port" -> "host:port": what the browser's Host header holds
// when the page came from this server.
std::string origin_authority(const std::string &origin)
{
    size_t scheme_end = origin.find("://");
    return scheme_end == std::string::npos ? origin : origin.substr(scheme_end + 3);
}

// Runs a handler of ours inside websocketpp's callbacks, where an exception
// would unwind through asio and stop the whole server.
template<typename Function>
void guarded(const char *what, Function &&function)
{
    try {
        function();
    } catch (const std::exception &error) {
        std::cerr << "aseba-ide: " << what << ": " << error.what() << "\n";
    }
}

} // namespace

struct WebServer::Implementation {
    Server server;
    WebServerOptions options;
    std::map<std::string, StaticFile, std::less<>> files;
    WebServerHandlers handlers;
    std::map<Handle, ConnectionId, std::owner_less<Handle>> ids;
    std::map<ConnectionId, Handle> handles;
    ConnectionId next_id = 1;

    Server::connection_ptr connection(ConnectionId id) const
    {
        auto found = handles.find(id);
        if (found == handles.end())
            return nullptr;
        websocketpp::lib::error_code error;
        Server::connection_ptr pointer =
          const_cast<Server &>(server).get_con_from_hdl(found->second, error);
        return error ? nullptr : pointer;
    }

    void serve_http(Handle handle)
    {
        Server::connection_ptr connection = server.get_con_from_hdl(handle);
        const std::string &method = connection->get_request().get_method();
        std::string path = connection->get_resource();
        path = path.substr(0, path.find_first_of("?#"));
        if (path == "/")
            path = "/index.html";
        connection->append_header("Cache-Control", "no-cache");
        connection->append_header("X-Content-Type-Options", "nosniff");
        if (method != "GET" && method != "HEAD") {
            connection->set_status(websocketpp::http::status_code::method_not_allowed);
            connection->append_header("Allow", "GET, HEAD");
            return;
        }
        auto found = files.find(path);
        if (found == files.end()) {
            connection->set_status(websocketpp::http::status_code::not_found);
            connection->append_header("Content-Type", "text/plain; charset=utf-8");
            connection->set_body("not found: " + path + "\n");
            return;
        }
        connection->set_status(websocketpp::http::status_code::ok);
        connection->append_header("Content-Type", std::string(found->second.content_type));
        // CodeMirror adds its styles in <style> elements, hence 'unsafe-inline'.
        connection->append_header("Content-Security-Policy",
                                  "default-src 'self'; style-src 'self' 'unsafe-inline'; "
                                  "img-src 'self' data: blob:; connect-src 'self'");
        connection->set_body(std::string(found->second.body));
    }

    // A WebSocket from a page of another site would let any web page the
    // user visits drive the robots: only this server's own page, or a
    // client that is no browser (no Origin), may open one.
    bool accept_websocket(Handle handle)
    {
        Server::connection_ptr connection = server.get_con_from_hdl(handle);
        const std::string &origin = connection->get_request_header("Origin");
        if (origin.empty() || origin_authority(origin) == connection->get_request_header("Host"))
            return true;
        connection->set_status(websocketpp::http::status_code::forbidden);
        return false;
    }

    void opened(Handle handle)
    {
        ConnectionId id = next_id++;
        ids[handle] = id;
        handles[id] = handle;
        std::string peer;
        websocketpp::lib::error_code error;
        if (Server::connection_ptr connection = server.get_con_from_hdl(handle, error))
            peer = connection->get_remote_endpoint();
        guarded("opening a connection", [&] { handlers.opened(id, peer); });
    }

    void closed(Handle handle)
    {
        auto found = ids.find(handle);
        if (found == ids.end())
            return;
        ConnectionId id = found->second;
        ids.erase(found);
        handles.erase(id);
        guarded("closing a connection", [&] { handlers.closed(id); });
    }

    void received(Handle handle, Server::message_ptr message)
    {
        auto found = ids.find(handle);
        if (found == ids.end())
            return;
        ConnectionId id = found->second;
        guarded("handling a message",
                [&] { handlers.received(id, std::move(message->get_raw_payload())); });
    }
};

WebServer::WebServer(asio::io_context &io,
                     const WebServerOptions &options,
                     std::vector<StaticFile> files,
                     WebServerHandlers handlers)
  : implementation_(std::make_unique<Implementation>())
{
    Implementation &self = *implementation_;
    self.options = options;
    self.handlers = std::move(handlers);
    for (const StaticFile &file : files)
        self.files[std::string(file.path)] = file;

    Server &server = self.server;
    server.clear_access_channels(websocketpp::log::alevel::all);
    server.clear_error_channels(websocketpp::log::elevel::all);
    server.init_asio(&io);
    server.set_reuse_addr(true);
    server.set_listen_backlog(asio::socket_base::max_listen_connections);
    server.set_max_message_size(options.max_message_bytes);
    // After accept: the socket is open only then.
    server.set_tcp_post_init_handler([&self](Handle handle) {
        websocketpp::lib::error_code error;
        Server::connection_ptr connection = self.server.get_con_from_hdl(handle, error);
        if (error)
            return;
        std::error_code ignored;
        auto &socket = connection->get_socket();
        socket.set_option(
          asio::socket_base::send_buffer_size(self.options.socket_send_buffer_bytes), ignored);
        socket.set_option(asio::ip::tcp::no_delay(true), ignored);
    });
    server.set_http_handler([&self](Handle handle) { self.serve_http(handle); });
    server.set_validate_handler([&self](Handle handle) { return self.accept_websocket(handle); });
    server.set_open_handler([&self](Handle handle) { self.opened(handle); });
    server.set_close_handler([&self](Handle handle) { self.closed(handle); });
    server.set_fail_handler([&self](Handle handle) { self.closed(handle); });
    server.set_message_handler(
      [&self](Handle handle, Server::message_ptr message) { self.received(handle, message); });

    std::error_code error;
    asio::ip::address address = asio::ip::make_address(options.bind_address, error);
    if (error)
        throw WebServerError("'" + options.bind_address + "' is not an IP address");
    websocketpp::lib::error_code listen_error;
    server.listen(asio::ip::tcp::endpoint(address, options.port), listen_error);
    if (listen_error)
        throw WebServerError("cannot listen on " + options.bind_address + " port " +
                             std::to_string(options.port) + ": " + listen_error.message());
    server.start_accept(listen_error);
    if (listen_error)
        throw WebServerError("cannot accept connections: " + listen_error.message());
}

WebServer::~WebServer() = default;

uint16_t WebServer::port() const
{
    std::error_code error;
    auto endpoint = implementation_->server.get_local_endpoint(error);
    return error ? 0 : endpoint.port();
}

bool WebServer::send(ConnectionId id, const std::string &text, Delivery delivery)
{
    Implementation &self = *implementation_;
    Server::connection_ptr connection = self.connection(id);
    if (!connection || connection->get_state() != websocketpp::session::state::open)
        return false;
    size_t waiting = connection->get_buffered_amount();
    if (waiting > 2 * self.options.max_buffered_bytes) {
        close(id, "the browser stopped reading");
        return false;
    }
    if (delivery == Delivery::skippable && waiting > self.options.max_buffered_bytes)
        return false;
    return !connection->send(text, websocketpp::frame::opcode::text);
}

size_t WebServer::buffered_bytes(ConnectionId id) const
{
    Server::connection_ptr connection = implementation_->connection(id);
    return connection ? connection->get_buffered_amount() : 0;
}

void WebServer::close(ConnectionId id, const std::string &reason)
{
    if (Server::connection_ptr connection = implementation_->connection(id)) {
        websocketpp::lib::error_code ignored;
        connection->close(websocketpp::close::status::policy_violation, reason, ignored);
    }
}

void WebServer::stop()
{
    Implementation &self = *implementation_;
    websocketpp::lib::error_code ignored;
    self.server.stop_listening(ignored);
    for (const auto &[id, handle] : self.handles) {
        if (Server::connection_ptr connection = self.connection(id))
            connection->close(websocketpp::close::status::going_away, "server stopping", ignored);
    }
}

} // namespace aseba::ide
