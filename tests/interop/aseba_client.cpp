#include "aseba_client.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <cstring>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdexcept>
#include <sys/socket.h>
#include <thread>
#include <unistd.h>

namespace interop
{

namespace
{

using Clock = std::chrono::steady_clock;

constexpr size_t header_size = 6;        // len, source, type (protocol.md §2)
constexpr size_t max_payload_size = 516; // protocol.md §2
constexpr auto connect_retry_interval = std::chrono::milliseconds(20);

// Reads a payload field by field and remembers any overread, so that a
// decoder can accept a payload only if it consumed it exactly.
class PayloadReader
{
  public:
    explicit PayloadReader(const std::vector<uint8_t> &payload)
      : payload_(payload)
    {
    }

    uint16_t word()
    {
        if (offset_ + 2 > payload_.size()) {
            failed_ = true;
            return 0;
        }
        uint16_t value = uint16_t(payload_[offset_] | (payload_[offset_ + 1] << 8));
        offset_ += 2;
        return value;
    }

    int16_t signed_word()
    {
        return int16_t(word());
    }

    // A string: one length byte, then that many bytes (no terminator).
    std::string text()
    {
        if (offset_ + 1 > payload_.size()) {
            failed_ = true;
            return {};
        }
        size_t length = payload_[offset_++];
        if (offset_ + length > payload_.size()) {
            failed_ = true;
            return {};
        }
        std::string value(payload_.begin() + long(offset_),
                          payload_.begin() + long(offset_ + length));
        offset_ += length;
        return value;
    }

    bool ok() const
    {
        return !failed_;
    }
    bool words_left() const
    {
        return offset_ < payload_.size();
    }
    // True if every field was there and nothing is left over.
    bool consumed_exactly() const
    {
        return !failed_ && offset_ == payload_.size();
    }

  private:
    const std::vector<uint8_t> &payload_;
    size_t offset_ = 0;
    bool failed_ = false;
};

template<typename Value>
std::optional<Value> if_exact(const PayloadReader &reader, Value value)
{
    if (!reader.consumed_exactly())
        return std::nullopt;
    return value;
}

std::chrono::milliseconds milliseconds_left(Clock::time_point deadline)
{
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    return left.count() > 0 ? left : std::chrono::milliseconds(0);
}

} // namespace

// --- decoders -------------------------------------------------------------

std::optional<VariablesMessage> decode_variables(const Frame &frame)
{
    if (frame.type != message::variables || frame.payload.size() % 2 != 0)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    VariablesMessage variables;
    variables.start = reader.word();
    while (reader.words_left())
        variables.values.push_back(reader.signed_word());
    return if_exact(reader, variables);
}

std::optional<ExecutionState> decode_execution_state(const Frame &frame)
{
    if (frame.type != message::execution_state_changed)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    ExecutionState state;
    state.pc = reader.word();
    state.flags = reader.word();
    return if_exact(reader, state);
}

std::optional<DescriptionHeader> decode_description(const Frame &frame)
{
    if (frame.type != message::description)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    DescriptionHeader header;
    header.name = reader.text();
    header.protocol_version = reader.word();
    header.bytecode_size = reader.word();
    header.stack_size = reader.word();
    header.variables_size = reader.word();
    header.named_variable_count = reader.word();
    header.local_event_count = reader.word();
    header.native_function_count = reader.word();
    return if_exact(reader, header);
}

std::optional<NamedVariable> decode_named_variable(const Frame &frame)
{
    if (frame.type != message::named_variable_description)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    NamedVariable variable;
    variable.size = reader.word();
    variable.name = reader.text();
    return if_exact(reader, variable);
}

std::optional<std::string> decode_local_event(const Frame &frame)
{
    if (frame.type != message::local_event_description)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    std::string name = reader.text();
    reader.text(); // description
    return if_exact(reader, name);
}

std::optional<std::string> decode_native_function(const Frame &frame)
{
    if (frame.type != message::native_function_description)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    std::string name = reader.text();
    reader.text(); // description
    uint16_t parameter_count = reader.word();
    for (uint16_t i = 0; i < parameter_count && reader.ok(); i++) {
        reader.signed_word(); // size or template id
        reader.text();        // parameter name
    }
    return if_exact(reader, name);
}

std::optional<OutOfBounds> decode_out_of_bounds(const Frame &frame)
{
    if (frame.type != message::array_access_out_of_bounds)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    OutOfBounds error;
    error.pc = reader.word();
    error.size = reader.word();
    error.index = reader.word();
    return if_exact(reader, error);
}

std::optional<uint16_t> decode_division_by_zero(const Frame &frame)
{
    if (frame.type != message::division_by_zero)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    uint16_t pc = reader.word();
    return if_exact(reader, pc);
}

std::optional<uint16_t> decode_node_present(const Frame &frame)
{
    if (frame.type != message::node_present)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    uint16_t version = reader.word();
    return if_exact(reader, version);
}

std::optional<std::vector<int16_t>> decode_user_event(const Frame &frame)
{
    if (!frame.is_user_event() || frame.payload.size() % 2 != 0)
        return std::nullopt;
    PayloadReader reader(frame.payload);
    std::vector<int16_t> arguments;
    while (reader.words_left())
        arguments.push_back(reader.signed_word());
    return if_exact(reader, arguments);
}

std::optional<uint16_t> NodeDescription::address_of(const std::string &name) const
{
    uint16_t address = 0;
    for (const auto &variable : variables) {
        if (variable.name == name)
            return address;
        address = uint16_t(address + variable.size);
    }
    return std::nullopt;
}

uint16_t NodeDescription::first_user_variable() const
{
    uint16_t address = 0;
    for (const auto &variable : variables)
        address = uint16_t(address + variable.size);
    return address;
}

// --- the connection -------------------------------------------------------

AsebaClient::AsebaClient(uint16_t port, Milliseconds timeout)
{
    auto deadline = Clock::now() + timeout;
    std::string last_error;
    for (;;) {
        socket_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (socket_ < 0)
            throw std::runtime_error(std::string("socket: ") + strerror(errno));
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        address.sin_port = htons(port);
        if (connect(socket_, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0)
            break;
        last_error = strerror(errno);
        close(socket_);
        socket_ = -1;
        if (Clock::now() >= deadline)
            throw std::runtime_error("cannot connect to 127.0.0.1:" + std::to_string(port) + ": " +
                                     last_error);
        std::this_thread::sleep_for(connect_retry_interval);
    }
    // We wait for answers to small requests: do not let Nagle delay them.
    int yes = 1;
    setsockopt(socket_, IPPROTO_TCP, TCP_NODELAY, &yes, sizeof yes);
}

AsebaClient::~AsebaClient()
{
    if (socket_ >= 0)
        close(socket_);
}

void AsebaClient::send(uint16_t type, const std::vector<int16_t> &words)
{
    std::vector<uint8_t> bytes;
    auto append = [&](uint16_t value) {
        bytes.push_back(uint8_t(value & 0xFF));
        bytes.push_back(uint8_t(value >> 8));
    };
    append(uint16_t(words.size() * 2));
    append(host_id);
    append(type);
    for (int16_t word : words)
        append(uint16_t(word));
    size_t sent = 0;
    while (sent < bytes.size()) {
        ssize_t count = ::send(socket_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
        if (count <= 0)
            throw std::runtime_error(std::string("send: ") + strerror(errno));
        sent += size_t(count);
    }
}

std::optional<Frame> AsebaClient::receive(Milliseconds timeout)
{
    auto deadline = Clock::now() + timeout;
    for (;;) {
        if (pending_.size() >= header_size) {
            size_t length = size_t(pending_[0] | (pending_[1] << 8));
            if (length > max_payload_size)
                throw std::runtime_error("the peer announced a payload of " +
                                         std::to_string(length) + " bytes");
            if (pending_.size() >= header_size + length) {
                Frame frame;
                frame.source = uint16_t(pending_[2] | (pending_[3] << 8));
                frame.type = uint16_t(pending_[4] | (pending_[5] << 8));
                frame.payload.assign(pending_.begin() + header_size,
                                     pending_.begin() + long(header_size + length));
                pending_.erase(pending_.begin(), pending_.begin() + long(header_size + length));
                return frame;
            }
        }
        auto left = milliseconds_left(deadline);
        pollfd readable = { socket_, POLLIN, 0 };
        int ready = poll(&readable, 1, int(left.count()));
        if (ready == 0)
            return std::nullopt;
        if (ready < 0) {
            if (errno == EINTR)
                continue;
            throw std::runtime_error(std::string("poll: ") + strerror(errno));
        }
        uint8_t buffer[4096];
        ssize_t count = recv(socket_, buffer, sizeof buffer, 0);
        if (count <= 0)
            throw std::runtime_error("the Aseba peer closed the connection");
        pending_.insert(pending_.end(), buffer, buffer + count);
    }
}

std::optional<Frame> AsebaClient::receive_until(const std::function<bool(const Frame &)> &wanted,
                                                Milliseconds timeout)
{
    auto deadline = Clock::now() + timeout;
    for (;;) {
        auto frame = receive(milliseconds_left(deadline));
        if (!frame)
            return std::nullopt;
        if (wanted(*frame))
            return frame;
        skipped_.push_back(std::move(*frame));
    }
}

std::vector<Frame> AsebaClient::collect(Milliseconds duration)
{
    auto deadline = Clock::now() + duration;
    std::vector<Frame> frames;
    while (auto frame = receive(milliseconds_left(deadline)))
        frames.push_back(std::move(*frame));
    return frames;
}

std::optional<std::vector<int16_t>> AsebaClient::read_variables(uint16_t node,
                                                                uint16_t start,
                                                                uint16_t count,
                                                                Milliseconds timeout)
{
    send(message::get_variables, { int16_t(node), int16_t(start), int16_t(count) });
    auto answer = receive_until(
      [&](const Frame &frame) {
          auto variables = decode_variables(frame);
          return frame.source == node && variables && variables->start == start;
      },
      timeout);
    if (!answer)
        return std::nullopt;
    return decode_variables(*answer)->values;
}

std::optional<NodeDescription> AsebaClient::describe(uint16_t node, Milliseconds timeout)
{
    send(message::get_node_description, { int16_t(node), int16_t(protocol_version) });
    return receive_description(node, timeout);
}

std::optional<NodeDescription> AsebaClient::receive_description(uint16_t node, Milliseconds timeout)
{
    auto deadline = Clock::now() + timeout;
    auto from_node = [&](uint16_t type) {
        return receive_until(
          [&](const Frame &frame) { return frame.source == node && frame.type == type; },
          milliseconds_left(deadline));
    };

    NodeDescription description;
    auto header_frame = from_node(message::description);
    auto header = header_frame ? decode_description(*header_frame) : std::nullopt;
    if (!header)
        return std::nullopt;
    description.header = *header;
    for (uint16_t i = 0; i < header->named_variable_count; i++) {
        auto frame = from_node(message::named_variable_description);
        auto variable = frame ? decode_named_variable(*frame) : std::nullopt;
        if (!variable)
            return std::nullopt;
        description.variables.push_back(*variable);
    }
    for (uint16_t i = 0; i < header->local_event_count; i++) {
        auto frame = from_node(message::local_event_description);
        auto name = frame ? decode_local_event(*frame) : std::nullopt;
        if (!name)
            return std::nullopt;
        description.local_events.push_back(*name);
    }
    for (uint16_t i = 0; i < header->native_function_count; i++) {
        auto frame = from_node(message::native_function_description);
        auto name = frame ? decode_native_function(*frame) : std::nullopt;
        if (!name)
            return std::nullopt;
        description.native_functions.push_back(*name);
    }
    return description;
}

} // namespace interop
