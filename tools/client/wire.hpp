// The framing of Aseba protocol 5 on stream transports (protocol.md §2): a
// frame is len, source, type (uint16 little-endian each), then len payload
// bytes. Here bytes become frames and frames become bytes; what the payload
// means is messages.hpp's concern.

#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace aseba::client
{

// Malformed input from the wire, or a message that cannot be put on it.
class ProtocolError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

constexpr size_t FRAME_HEADER_SIZE = 6;
constexpr size_t MAX_PAYLOAD_SIZE = 516; // 258 words; upstream hosts abort on more
constexpr size_t MAX_STRING_SIZE = 255;  // a string is a length byte and its bytes
constexpr uint16_t HOST_SOURCE = 0;      // the source id of hosts

struct Frame {
    uint16_t source = 0;
    uint16_t type = 0;
    std::vector<uint8_t> payload;
};

// The bytes of `frame` on the wire; throws ProtocolError if its payload is
// longer than the protocol allows.
std::vector<uint8_t> serialize_frame(const Frame &frame);

// Cuts a byte stream into frames. A header announcing a payload above the
// maximum cannot be skipped (there is no resynchronisation marker), so the
// stream is then broken for good.
class FrameAssembler
{
  public:
    // Takes bytes from the stream; throws ProtocolError if it is broken.
    void feed(const uint8_t *bytes, size_t count);

    // The next complete frame, if one has arrived; throws ProtocolError when
    // the next header announces an impossible length (the stream is broken).
    std::optional<Frame> next();

    // Bytes received but not yet part of a complete frame.
    size_t pending_bytes() const
    {
        return pending_.size() - consumed_;
    }

  private:
    std::vector<uint8_t> pending_;
    size_t consumed_ = 0;
    bool broken_ = false;
};

// Reads little-endian fields from a payload; every read checks the bounds and
// throws ProtocolError with `what` (the message name) when the payload is too
// short.
class PayloadReader
{
  public:
    PayloadReader(const std::vector<uint8_t> &payload, const char *what)
      : payload_(payload)
      , what_(what)
    {
    }
    uint16_t u16();
    int16_t i16()
    {
        return int16_t(u16());
    }
    uint8_t byte();
    std::string string();
    size_t remaining() const
    {
        return payload_.size() - position_;
    }
    // Throws unless every byte was consumed (upstream hosts are that strict).
    void expect_end() const;

  private:
    [[noreturn]] void too_short() const;
    const std::vector<uint8_t> &payload_;
    const char *what_;
    size_t position_ = 0;
};

// Appends little-endian fields to a payload; strings longer than the protocol
// allows throw ProtocolError.
class PayloadWriter
{
  public:
    void u16(uint16_t value);
    void i16(int16_t value)
    {
        u16(uint16_t(value));
    }
    void byte(uint8_t value)
    {
        bytes_.push_back(value);
    }
    void string(const std::string &text);
    std::vector<uint8_t> take()
    {
        return std::move(bytes_);
    }

  private:
    std::vector<uint8_t> bytes_;
};

} // namespace aseba::client
