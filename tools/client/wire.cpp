// Framing and field encoding of protocol.md §2.

#include "wire.hpp"

namespace aseba::client
{

namespace
{

uint16_t read_u16(const uint8_t *bytes)
{
    return uint16_t(bytes[0] | (bytes[1] << 8));
}

void append_u16(std::vector<uint8_t> &bytes, uint16_t value)
{
    bytes.push_back(uint8_t(value & 0xFF));
    bytes.push_back(uint8_t(value >> 8));
}

} // namespace

std::vector<uint8_t> serialize_frame(const Frame &frame)
{
    if (frame.payload.size() > MAX_PAYLOAD_SIZE)
        throw ProtocolError("message of " + std::to_string(frame.payload.size()) +
                            " payload bytes is longer than the protocol's " +
                            std::to_string(MAX_PAYLOAD_SIZE));
    std::vector<uint8_t> bytes;
    bytes.reserve(FRAME_HEADER_SIZE + frame.payload.size());
    append_u16(bytes, uint16_t(frame.payload.size()));
    append_u16(bytes, frame.source);
    append_u16(bytes, frame.type);
    bytes.insert(bytes.end(), frame.payload.begin(), frame.payload.end());
    return bytes;
}

void FrameAssembler::feed(const uint8_t *bytes, size_t count)
{
    if (broken_)
        throw ProtocolError("the stream lost its framing earlier");
    // Drop what earlier frames used before the buffer grows again.
    if (consumed_ > 0) {
        pending_.erase(pending_.begin(), pending_.begin() + long(consumed_));
        consumed_ = 0;
    }
    pending_.insert(pending_.end(), bytes, bytes + count);
}

std::optional<Frame> FrameAssembler::next()
{
    if (broken_)
        throw ProtocolError("the stream lost its framing earlier");
    size_t available = pending_.size() - consumed_;
    if (available < 2)
        return std::nullopt;
    const uint8_t *header = pending_.data() + consumed_;
    uint16_t length = read_u16(header);
    if (length > MAX_PAYLOAD_SIZE) {
        broken_ = true;
        throw ProtocolError("a frame announces " + std::to_string(length) +
                            " payload bytes, more than the protocol's " +
                            std::to_string(MAX_PAYLOAD_SIZE) + "; the stream cannot be followed");
    }
    if (available < FRAME_HEADER_SIZE + length)
        return std::nullopt;
    Frame frame;
    frame.source = read_u16(header + 2);
    frame.type = read_u16(header + 4);
    frame.payload.assign(header + FRAME_HEADER_SIZE, header + FRAME_HEADER_SIZE + length);
    consumed_ += FRAME_HEADER_SIZE + length;
    return frame;
}

void PayloadReader::too_short() const
{
    throw ProtocolError(std::string(what_) + ": payload of " + std::to_string(payload_.size()) +
                        " bytes is too short for its layout");
}

uint16_t PayloadReader::u16()
{
    if (remaining() < 2)
        too_short();
    uint16_t value = read_u16(payload_.data() + position_);
    position_ += 2;
    return value;
}

uint8_t PayloadReader::byte()
{
    if (remaining() < 1)
        too_short();
    return payload_[position_++];
}

std::string PayloadReader::string()
{
    size_t length = byte();
    if (remaining() < length)
        too_short();
    std::string text(payload_.begin() + long(position_),
                     payload_.begin() + long(position_ + length));
    position_ += length;
    return text;
}

void PayloadReader::expect_end() const
{
    if (remaining() != 0)
        throw ProtocolError(std::string(what_) + ": " + std::to_string(remaining()) +
                            " unexpected bytes after the layout's end");
}

void PayloadWriter::u16(uint16_t value)
{
    append_u16(bytes_, value);
}

void PayloadWriter::string(const std::string &text)
{
    if (text.size() > MAX_STRING_SIZE)
        throw ProtocolError("string of " + std::to_string(text.size()) +
                            " bytes is longer than the protocol's " +
                            std::to_string(MAX_STRING_SIZE));
    bytes_.push_back(uint8_t(text.size()));
    bytes_.insert(bytes_.end(), text.begin(), text.end());
}

} // namespace aseba::client
