// The links of the client library over standalone asio: one byte stream,
// a TCP socket or a serial port, on a caller's io_context. Private to the
// library (transport.cpp, network.cpp), so that users of transport.hpp and
// network.hpp never compile asio.

#pragma once

// Standalone asio, not Boost's. Its aligned allocation depends on a macro
// the standard library defines only once one of its headers is in, so two
// files could choose differently and free with the wrong function: use
// operator new and delete everywhere.
#define ASIO_STANDALONE
#define ASIO_DISABLE_STD_ALIGNED_ALLOC
#include <asio.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <variant>

#include "transport.hpp"

namespace aseba::client::detail
{

class ByteStream
{
  public:
    using Handler = std::function<void(std::error_code, size_t)>;
    // Called once an asynchronous opening ends: empty on success, else why
    // it failed, as a sentence.
    using OpenHandler = std::function<void(const std::string &failure)>;

    explicit ByteStream(asio::io_context &io);
    ~ByteStream();
    ByteStream(const ByteStream &) = delete;
    ByteStream &operator=(const ByteStream &) = delete;

    // Opens the link, running the io_context for at most `timeout`; throws
    // TransportError with the system's reason.
    void open(const TargetAddress &address, std::chrono::milliseconds timeout);

    // Starts opening the link; `done` is called from the io_context, within
    // about `timeout`. A serial device opens at once (`done` is then called
    // before this returns).
    void async_open(const TargetAddress &address,
                    std::chrono::milliseconds timeout,
                    OpenHandler done);

    bool is_open() const;
    void close();
    int native_handle();

    void async_read_some(asio::mutable_buffer buffer, Handler handler);
    void async_write(asio::const_buffer buffer, Handler handler);
    // Reads what is there without waiting (would_block when nothing is).
    size_t read_some(asio::mutable_buffer buffer, std::error_code &error);

    // Writes every byte, running the io_context for at most `timeout`;
    // throws TransportError (naming `name`) when the link fails or takes
    // nothing for that long.
    void write_all(const uint8_t *bytes,
                   size_t count,
                   std::chrono::milliseconds timeout,
                   const std::string &name);

  private:
    void open_serial(const TargetAddress &address);
    asio::io_context &io_;
    // Which stream is open (none before open()).
    std::variant<std::monostate, asio::ip::tcp::socket, asio::serial_port> stream_;
    // What an asynchronous opening shares with its handlers, which may
    // outlive this object's interest in them (a closed link).
    struct Opening;
    std::shared_ptr<Opening> opening_;
};

} // namespace aseba::client::detail
