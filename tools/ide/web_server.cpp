// websocketpp behind WebServer. This file alone is compiled as C++17: the
// headers of websocketpp 0.8.2 (Debian 12) declare constructors with
// template-ids, which C++20 rejects; nothing of them leaks into the header.

#include "web_server.hpp"

#include <algorithm>
#include <cctype>
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

// The host of a Host header ("name:port", "[v6]:port"), in lower case,
// without its port and a final dot.
std::string host_name_of(std::string host)
{
    if (!host.empty() && host.front() == '[')
        host = host.substr(1, host.find(']') - 1);
    else if (size_t colon = host.find(':'); colon != std::string::npos)
        host.resize(colon);
    std::transform(host.begin(), host.end(), host.begin(), [](unsigned char c) {
        return char(std::tolower(c));
    });
    if (!host.empty() && host.back() == '.')
        host.pop_back();
    return host;
}

bool ends_with(const std::string &text, const std::string &end)
{
    return text.size() >= end.size() &&
           text.compare(text.size() - end.size(), end.size(), end) == 0;
}

// Whether a browser that names `host` in its Host header reached this server
// by a name no other site controls: a loopback name (browsers resolve
// *.localhost themselves), an IP address, or a name it was told about.
bool host_allowed(const std::string &host, const std::vector<std::string> &host_names)
{
    std::string name = host_name_of(host);
    if (name.empty())
        return false;
    if (name == "localhost" || ends_with(name, ".localhost"))
        return true;
    std::error_code not_an_address;
    asio::ip::make_address(name, not_an_address);
    if (!not_an_address)
        return true;
    return std::any_of(host_names.begin(), host_names.end(), [&](const std::string &known) {
        return host_name_of(known) == name;
    });
}

// Compares in a time that does not depend on where the texts differ.
bool same_secret(const std::string &given, const std::string &secret)
{
    if (secret.empty())
        return false;
    unsigned char difference = given.size() == secret.size() ? 0 : 1;
    for (size_t i = 0; i < given.size(); i++)
        difference |= (unsigned char)(given[i] ^ secret[i % secret.size()]);
    return difference == 0;
}

// The value of `name` in a query string ("a=1&token=x") or a Cookie header
// ("a=1; token=x"), "" when absent.
std::string field_value(const std::string &text, const std::string &name, char separator)
{
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find(separator, start);
        if (end == std::string::npos)
            end = text.size();
        std::string field = text.substr(start, end - start);
        field.erase(0, field.find_first_not_of(' '));
        if (field.rfind(name + "=", 0) == 0)
            return field.substr(name.size() + 1);
        start = end + 1;
    }
    return "";
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
    // Every connection held (pages, files and WebSockets alike), with when
    // it last said something: a request, a message.
    std::map<Handle, connections::Clock::time_point, std::owner_less<Handle>> heard;
    std::string cookie_name;

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

    // A connection beyond the cap takes the place of the one silent the
    // longest, if silent long enough; else it is closed before it is read.
    void admit(Handle handle)
    {
        auto now = connections::Clock::now();
        for (auto held = heard.begin(); held != heard.end();)
            held = held->first.expired() ? heard.erase(held) : std::next(held);
        websocketpp::lib::error_code ignored;
        Server::connection_ptr connection = server.get_con_from_hdl(handle, ignored);
        if (!connection)
            return;
        if (heard.size() >= options.connections.capacity) {
            auto quietest = connections::client_giving_way(
              heard.begin(),
              heard.end(),
              [](const auto &held) { return held.second; },
              options.connections,
              now);
            if (quietest == heard.end()) {
                connection->get_raw_socket().close(ignored);
                return;
            }
            if (Server::connection_ptr idle = server.get_con_from_hdl(quietest->first, ignored))
                idle->terminate(ignored);
            heard.erase(quietest);
        }
        heard[handle] = now;
    }

    void heard_from(Handle handle)
    {
        if (auto held = heard.find(handle); held != heard.end())
            held->second = connections::Clock::now();
    }

    // Why a request may not be served (its Host, its token), or "".
    std::string refusal(const Server::connection_ptr &connection) const
    {
        const std::string &host = connection->get_request_header("Host");
        if (!host_allowed(host, options.host_names))
            return "aseba-ide does not serve the name '" + host_name_of(host) +
                   "' (a page of another site may have renamed this computer): open it as "
                   "localhost, by its address, or by a name given with --allow-host\n";
        if (options.access_token.empty())
            return "";
        std::string resource = connection->get_resource();
        size_t query = resource.find('?');
        std::string given =
          query == std::string::npos ? "" : field_value(resource.substr(query + 1), "token", '&');
        if (given.empty())
            given = field_value(connection->get_request_header("Cookie"), cookie_name, ';');
        if (same_secret(given, options.access_token))
            return "";
        return "this aseba-ide is open to the network: open the address it printed at start, "
               "with its ?token=\n";
    }

    void serve_http(Handle handle)
    {
        heard_from(handle);
        Server::connection_ptr connection = server.get_con_from_hdl(handle);
        const std::string &method = connection->get_request().get_method();
        std::string path = connection->get_resource();
        path = path.substr(0, path.find_first_of("?#"));
        if (path == "/")
            path = "/index.html";
        connection->append_header("Cache-Control", "no-cache");
        connection->append_header("X-Content-Type-Options", "nosniff");
        if (std::string refused = refusal(connection); !refused.empty()) {
            connection->set_status(websocketpp::http::status_code::forbidden);
            connection->append_header("Content-Type", "text/plain; charset=utf-8");
            connection->set_body(refused);
            return;
        }
        // The page's own requests (its files, its WebSocket) carry the token
        // in this cookie; the browser sends it to this computer only.
        if (!options.access_token.empty())
            connection->append_header("Set-Cookie",
                                      cookie_name + "=" + options.access_token +
                                        "; Path=/; HttpOnly; SameSite=Strict");
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
    // client that is no browser (no Origin), may open one, under a name of
    // this server and with the token when one is needed.
    bool accept_websocket(Handle handle)
    {
        heard_from(handle);
        Server::connection_ptr connection = server.get_con_from_hdl(handle);
        const std::string &origin = connection->get_request_header("Origin");
        bool same_origin =
          origin.empty() || origin_authority(origin) == connection->get_request_header("Host");
        if (same_origin && refusal(connection).empty())
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
        heard_from(handle);
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
        self.admit(handle);
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
    self.cookie_name = token_cookie_name(port());
}

bool is_loopback_address(const std::string &address)
{
    std::error_code error;
    asio::ip::address parsed = asio::ip::make_address(address, error);
    return !error && parsed.is_loopback();
}

std::string token_cookie_name(uint16_t port)
{
    return "aseba-ide-token-" + std::to_string(port);
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
