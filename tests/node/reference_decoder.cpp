#include "reference_decoder.hpp"

#include <memory>
#include <typeinfo>

#include <common/msg/msg.h>

namespace node_test
{

std::string reference_check(const Bytes &frame)
{
    Aseba::Message::SerializationBuffer buffer;
    buffer.rawData.assign(frame.begin() + 6, frame.end());
    uint16_t source = uint16_t(frame[2] | frame[3] << 8);
    uint16_t type = uint16_t(frame[4] | frame[5] << 8);
    std::unique_ptr<Aseba::Message> message(Aseba::Message::create(source, type, buffer));
    if (!message)
        return "upstream made no message of type " + std::to_string(type);
    // Upstream reads any type it does not know as a user message.
    if (type >= 0x8000 && dynamic_cast<Aseba::UserMessage *>(message.get()) != nullptr)
        return "upstream does not know type " + std::to_string(type);
    if (buffer.readPos != buffer.rawData.size())
        return "upstream read " + std::to_string(buffer.readPos) + " of " +
               std::to_string(buffer.rawData.size()) + " payload bytes";
    return "";
}

} // namespace node_test
