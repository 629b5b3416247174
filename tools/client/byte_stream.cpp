// TCP sockets and serial ports over standalone asio (see byte_stream.hpp).

#include "byte_stream.hpp"

#include <cerrno>
#include <sys/ioctl.h>
#include <termios.h>
#include <vector>

namespace aseba::client::detail
{

using Milliseconds = std::chrono::milliseconds;

struct ByteStream::Opening {
    explicit Opening(asio::io_context &io)
      : resolver(io)
      , timer(io)
      , socket(io)
    {
    }
    asio::ip::tcp::resolver resolver;
    asio::steady_timer timer;
    asio::ip::tcp::socket socket;
    std::string name;
    Milliseconds timeout{};
    OpenHandler done;
    bool timed_out = false;
    bool cancelled = false; // closed by the owner: no handler may touch it
};

ByteStream::ByteStream(asio::io_context &io)
  : io_(io)
{
}

ByteStream::~ByteStream()
{
    close();
}

bool ByteStream::is_open() const
{
    return !std::holds_alternative<std::monostate>(stream_);
}

void ByteStream::close()
{
    if (opening_) {
        opening_->cancelled = true;
        std::error_code ignored;
        opening_->resolver.cancel();
        opening_->socket.close(ignored);
        opening_->timer.cancel();
        opening_.reset();
    }
    std::visit(
      [](auto &stream) {
          if constexpr (!std::is_same_v<std::decay_t<decltype(stream)>, std::monostate>) {
              std::error_code ignored;
              stream.close(ignored);
          }
      },
      stream_);
    stream_ = std::monostate{};
}

int ByteStream::native_handle()
{
    if (auto *socket = std::get_if<asio::ip::tcp::socket>(&stream_))
        return socket->native_handle();
    if (auto *port = std::get_if<asio::serial_port>(&stream_))
        return port->native_handle();
    return -1;
}

void ByteStream::open_serial(const TargetAddress &address)
{
    std::string name = target_text(address);
    asio::serial_port port(io_);
    std::error_code error;
    port.open(address.device, error);
    if (error.value() == ENOTTY) // the device answers no terminal request
        throw TransportError(name + ": not a serial device (" + address.device + ")");
    if (error)
        throw TransportError(name + ": cannot open " + address.device + ": " + error.message());
    // Raw 8N1 without flow control, like Dashel's defaults (protocol.md §8.2);
    // asio opens ports raw.
    port.set_option(asio::serial_port_base::baud_rate(address.baud), error);
    if (error)
        throw TransportError(name + ": unsupported baud rate " + std::to_string(address.baud));
    using base = asio::serial_port_base;
    port.set_option(base::character_size(8), error);
    if (!error)
        port.set_option(base::parity(base::parity::none), error);
    if (!error)
        port.set_option(base::stop_bits(base::stop_bits::one), error);
    if (!error)
        port.set_option(base::flow_control(base::flow_control::none), error);
    if (error)
        throw TransportError(name + ": cannot configure the port: " + error.message());
    int fd = port.native_handle();
    termios settings{};
    if (tcgetattr(fd, &settings) == 0) {
        // Reads return what is there, at once.
        settings.c_cc[VMIN] = 0;
        settings.c_cc[VTIME] = 0;
        tcsetattr(fd, TCSANOW, &settings);
    }
    int dtr = TIOCM_DTR;
    ioctl(fd, TIOCMBIS, &dtr); // some adapters have no modem lines: not an error
    tcflush(fd, TCIOFLUSH);
    stream_.emplace<asio::serial_port>(std::move(port));
}

void ByteStream::async_open(const TargetAddress &address, Milliseconds timeout, OpenHandler done)
{
    close();
    if (address.kind == TargetAddress::Kind::serial) {
        std::string failure;
        try {
            open_serial(address);
        } catch (const TransportError &error) {
            failure = error.what();
        }
        done(failure);
        return;
    }
    auto opening = std::make_shared<Opening>(io_);
    opening->name = target_text(address);
    opening->timeout = timeout;
    opening->done = std::move(done);
    opening_ = opening;

    auto finish = [this, opening](const std::string &failure) {
        opening->timer.cancel();
        if (failure.empty()) {
            std::error_code ignored;
            // Hosts wait for each answer: do not let Nagle hold small frames.
            opening->socket.set_option(asio::ip::tcp::no_delay(true), ignored);
            stream_.emplace<asio::ip::tcp::socket>(std::move(opening->socket));
        }
        opening_.reset();
        OpenHandler handler = std::move(opening->done);
        handler(failure.empty() ? failure : opening->name + ": " + failure);
    };
    auto reason = [opening](const std::error_code &error) {
        return opening->timed_out
                 ? "timed out after " + std::to_string(opening->timeout.count()) + " ms"
                 : error.message();
    };
    opening->timer.expires_after(timeout);
    opening->timer.async_wait([opening](std::error_code error) {
        if (error || opening->cancelled)
            return;
        opening->timed_out = true;
        std::error_code ignored;
        opening->resolver.cancel();
        opening->socket.close(ignored);
    });
    auto connect = [opening, finish, reason](const auto &endpoints) {
        asio::async_connect(
          opening->socket,
          endpoints,
          [opening, finish, reason](std::error_code failed, const asio::ip::tcp::endpoint &) {
              if (opening->cancelled)
                  return;
              finish(failed ? "cannot connect: " + reason(failed) : "");
          });
    };
    // An address needs no resolver (whose thread takes time to start).
    std::error_code not_an_address;
    asio::ip::address ip = asio::ip::make_address(address.host, not_an_address);
    if (!not_an_address) {
        connect(std::vector<asio::ip::tcp::endpoint>{ { ip, address.port } });
        return;
    }
    std::string host = address.host;
    opening->resolver.async_resolve(
      host,
      std::to_string(address.port),
      [opening, finish, reason, host, connect](std::error_code error,
                                               asio::ip::tcp::resolver::results_type endpoints) {
          if (opening->cancelled)
              return;
          if (error) {
              finish("cannot resolve '" + host + "': " + reason(error));
              return;
          }
          connect(endpoints);
      });
}

namespace
{

// Runs `io` until `done` or `deadline`; false when the deadline came first.
bool run_until(asio::io_context &io,
               const bool &done,
               std::chrono::steady_clock::time_point deadline)
{
    while (!done) {
        if (io.stopped())
            io.restart();
        if (io.run_one_until(deadline) == 0 && std::chrono::steady_clock::now() >= deadline)
            return done;
    }
    return true;
}

// Runs `io` until `done`, which a cancelled operation's handler sets soon.
void run_until_done(asio::io_context &io, const bool &done)
{
    while (!done) {
        if (io.stopped())
            io.restart();
        io.run_one();
    }
}

} // namespace

void ByteStream::open(const TargetAddress &address, Milliseconds timeout)
{
    bool done = false;
    std::string failure;
    async_open(address, timeout, [&](const std::string &result) {
        done = true;
        failure = result;
    });
    // The opening's own timer ends it within `timeout`.
    run_until_done(io_, done);
    if (!failure.empty())
        throw TransportError(failure);
}

void ByteStream::async_read_some(asio::mutable_buffer buffer, Handler handler)
{
    if (auto *socket = std::get_if<asio::ip::tcp::socket>(&stream_))
        socket->async_read_some(buffer, std::move(handler));
    else if (auto *port = std::get_if<asio::serial_port>(&stream_))
        port->async_read_some(buffer, std::move(handler));
    else
        asio::post(io_, [handler] { handler(asio::error::not_connected, 0); });
}

void ByteStream::async_write(asio::const_buffer buffer, Handler handler)
{
    if (auto *socket = std::get_if<asio::ip::tcp::socket>(&stream_))
        asio::async_write(*socket, buffer, std::move(handler));
    else if (auto *port = std::get_if<asio::serial_port>(&stream_))
        asio::async_write(*port, buffer, std::move(handler));
    else
        asio::post(io_, [handler] { handler(asio::error::not_connected, 0); });
}

size_t ByteStream::read_some(asio::mutable_buffer buffer, std::error_code &error)
{
    error.clear();
    int fd = native_handle();
    if (fd < 0) {
        error = asio::error::not_connected;
        return 0;
    }
    ssize_t count = ::read(fd, buffer.data(), buffer.size());
    if (count > 0)
        return size_t(count);
    if (count == 0)
        error = asio::error::eof;
    else if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)
        error = asio::error::would_block;
    else
        error = std::error_code(errno, std::system_category());
    return 0;
}

void ByteStream::write_all(const uint8_t *bytes,
                           size_t count,
                           Milliseconds timeout,
                           const std::string &name)
{
    bool done = false;
    std::error_code result;
    async_write(asio::buffer(bytes, count), [&](std::error_code error, size_t) {
        done = true;
        result = error;
    });
    if (!run_until(io_, done, std::chrono::steady_clock::now() + timeout)) {
        // The handler refers to this frame: let it run, cancelled.
        close();
        run_until_done(io_, done);
        throw TransportError(name + ": the link takes no data (timed out after " +
                             std::to_string(timeout.count()) + " ms)");
    }
    if (result)
        throw TransportError(name + ": write failed: " + result.message());
}

} // namespace aseba::client::detail
