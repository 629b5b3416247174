// The control port on standalone asio (see control_port.hpp).

#include "control_port.hpp"

#include <deque>
#include <list>
#include <stdexcept>

#include <asio/buffer.hpp>
#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/read_until.hpp>
#include <asio/streambuf.hpp>
#include <asio/write.hpp>

namespace aseba::arena
{

using asio::ip::tcp;

namespace
{

// A web page can make the browser send a request to any port of this
// computer, with a body of its choosing: its request line ("POST /
// HTTP/1.1") ends the connection before any line of that body runs.
bool is_http_request_line(const std::string &line)
{
    size_t last_space = line.rfind(' ');
    return last_space != std::string::npos && line.compare(last_space + 1, 5, "HTTP/") == 0;
}

} // namespace

struct ControlPort::Implementation {
    struct Client {
        explicit Client(tcp::socket connected)
          : socket(std::move(connected))
          , input(longest_line + 1)
        {
        }
        tcp::socket socket;
        asio::streambuf input;
        std::deque<std::string> answers; // the front one is being written
        connections::Clock::time_point heard = connections::Clock::now(); // its last line
        bool closed = false;
        unsigned pending = 0; // operations whose handler has not run: they hold &client
        bool leave_after_answers = false;

        void close()
        {
            closed = true;
            std::error_code ignored;
            socket.close(ignored);
        }
    };

    Handler handler;
    connections::PortLimit limit;
    asio::io_context io;
    tcp::acceptor acceptor{ io };
    std::list<Client> clients;
    bool accepting = false;

    void accept()
    {
        accepting = true;
        acceptor.async_accept([this](const std::error_code &error, tcp::socket socket) {
            accepting = false;
            if (error)
                return; // tried again at the next service()
            if (make_room())
                read(clients.emplace_back(std::move(socket)));
            accept();
        });
    }

    // Whether a newcomer may stay: the port has room, or its client silent
    // the longest has been for the grace and leaves.
    bool make_room()
    {
        return connections::make_room(
          clients,
          [](const Client &member) { return !member.closed; },
          [](const Client &member) { return member.heard; },
          [](Client &member) { member.close(); },
          limit);
    }

    void read(Client &client)
    {
        client.pending++;
        asio::async_read_until(
          client.socket, client.input, '\n', [this, &client](const std::error_code &error, size_t) {
              client.pending--;
              if (client.closed)
                  return;
              if (error == asio::error::not_found) {
                  // The buffer's limit: no line end within longest_line.
                  answer(client,
                         "error: a command line is at most " + std::to_string(longest_line) +
                           " characters");
                  client.leave_after_answers = true;
                  return;
              }
              if (error) {
                  client.close();
                  return;
              }
              client.heard = connections::Clock::now();
              std::string line;
              std::istream stream(&client.input);
              std::getline(stream, line);
              if (!line.empty() && line.back() == '\r')
                  line.pop_back();
              if (is_http_request_line(line)) {
                  client.close();
                  return;
              }
              if (line.find_first_not_of(" \t") != std::string::npos)
                  answer(client, handler(line));
              read(client);
          });
    }

    void answer(Client &client, const std::string &text)
    {
        client.answers.push_back(text + "\n");
        if (client.answers.size() == 1)
            write(client);
    }

    void write(Client &client)
    {
        client.pending++;
        asio::async_write(client.socket,
                          asio::buffer(client.answers.front()),
                          [this, &client](const std::error_code &error, size_t) {
                              client.pending--;
                              if (error || client.closed) {
                                  client.close();
                                  return;
                              }
                              client.answers.pop_front();
                              if (!client.answers.empty())
                                  write(client);
                              else if (client.leave_after_answers)
                                  client.close();
                          });
    }
};

ControlPort::ControlPort(uint16_t port, Handler handler, const connections::PortLimit &limit)
  : implementation_(std::make_unique<Implementation>())
{
    Implementation &self = *implementation_;
    self.handler = std::move(handler);
    self.limit = limit;
    std::error_code error;
    tcp::endpoint endpoint(asio::ip::address_v4::loopback(), port);
    self.acceptor.open(endpoint.protocol(), error);
    if (!error)
        self.acceptor.set_option(tcp::acceptor::reuse_address(true), error);
    if (!error)
        self.acceptor.bind(endpoint, error);
    if (!error)
        self.acceptor.listen(asio::socket_base::max_listen_connections, error);
    if (error)
        throw std::runtime_error("cannot open the control port on 127.0.0.1 port " +
                                 std::to_string(port) + ": " + error.message());
    self.accept();
}

ControlPort::~ControlPort() = default;

uint16_t ControlPort::port() const
{
    return implementation_->acceptor.local_endpoint().port();
}

void ControlPort::service()
{
    Implementation &self = *implementation_;
    self.io.poll();
    self.io.restart();
    self.clients.remove_if(
      [](const Implementation::Client &client) { return client.closed && client.pending == 0; });
    if (!self.accepting)
        self.accept();
}

size_t ControlPort::client_count() const
{
    return implementation_->clients.size();
}

} // namespace aseba::arena
