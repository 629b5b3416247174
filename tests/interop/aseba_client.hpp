// A minimal Aseba protocol-5 host, written from ../shared/spec/protocol.md
// alone, so that the tests observe the node independently of the node's own
// code (vm/node*.c) and of the reference tools under test. Every decoder is
// strict: a payload that its layout does not consume exactly is rejected.

#ifndef INTEROP_ASEBA_CLIENT_HPP
#define INTEROP_ASEBA_CLIENT_HPP

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace interop
{

// Message types of protocol.md §3 that the tests use.
namespace message
{
constexpr uint16_t first_system_type = 0x8000; // below: user events
constexpr uint16_t description = 0x9000;
constexpr uint16_t named_variable_description = 0x9001;
constexpr uint16_t local_event_description = 0x9002;
constexpr uint16_t native_function_description = 0x9003;
constexpr uint16_t variables = 0x9005;
constexpr uint16_t array_access_out_of_bounds = 0x9006;
constexpr uint16_t division_by_zero = 0x9007;
constexpr uint16_t execution_state_changed = 0x900A;
constexpr uint16_t node_present = 0x900C;
constexpr uint16_t run = 0xA003;
constexpr uint16_t get_variables = 0xA00B;
constexpr uint16_t set_variables = 0xA00C;
constexpr uint16_t suspend_to_ram = 0xA00F;
constexpr uint16_t get_node_description = 0xA010;
constexpr uint16_t list_nodes = 0xA011;
} // namespace message

constexpr uint16_t protocol_version = 5;
constexpr uint16_t host_id = 0; // the source of every frame a host sends

// One frame of protocol.md §2, header decoded.
struct Frame {
    uint16_t source = 0;
    uint16_t type = 0;
    std::vector<uint8_t> payload;

    bool is_user_event() const
    {
        return type < message::first_system_type;
    }
};

// --- decoders: nullopt unless the payload has exactly the layout ----------

struct VariablesMessage {
    uint16_t start = 0;
    std::vector<int16_t> values;
};
struct ExecutionState {
    uint16_t pc = 0;
    uint16_t flags = 0;
};
struct DescriptionHeader {
    std::string name;
    uint16_t protocol_version = 0;
    uint16_t bytecode_size = 0;
    uint16_t stack_size = 0;
    uint16_t variables_size = 0;
    uint16_t named_variable_count = 0;
    uint16_t local_event_count = 0;
    uint16_t native_function_count = 0;
};
struct NamedVariable {
    uint16_t size = 0;
    std::string name;
};
struct OutOfBounds {
    uint16_t pc = 0;
    uint16_t size = 0;
    uint16_t index = 0;
};

std::optional<VariablesMessage> decode_variables(const Frame &frame);
std::optional<ExecutionState> decode_execution_state(const Frame &frame);
std::optional<DescriptionHeader> decode_description(const Frame &frame);
std::optional<NamedVariable> decode_named_variable(const Frame &frame);
// A local event description: its name (the documentation string is checked
// for layout only).
std::optional<std::string> decode_local_event(const Frame &frame);
// A native function description: its name (the rest is checked for layout).
std::optional<std::string> decode_native_function(const Frame &frame);
std::optional<OutOfBounds> decode_out_of_bounds(const Frame &frame);
// DIVISION_BY_ZERO: its pc.
std::optional<uint16_t> decode_division_by_zero(const Frame &frame);
// NODE_PRESENT: the node's protocol version.
std::optional<uint16_t> decode_node_present(const Frame &frame);
// A user event's arguments (nullopt for an odd payload length).
std::optional<std::vector<int16_t>> decode_user_event(const Frame &frame);

// A node's complete description, as a host learns it (protocol.md §6.1).
struct NodeDescription {
    DescriptionHeader header;
    std::vector<NamedVariable> variables;
    std::vector<std::string> local_events;
    std::vector<std::string> native_functions;

    // The address of a named variable: the sum of the sizes before it
    // (protocol.md §6.6); nullopt if the node has no such variable.
    std::optional<uint16_t> address_of(const std::string &name) const;
    // Where the compiler puts the first user variable (language.md §7).
    uint16_t first_user_variable() const;
};

// A TCP connection to an Aseba network (a node or a switch).
class AsebaClient
{
  public:
    using Milliseconds = std::chrono::milliseconds;

    // Connects to 127.0.0.1:port, retrying until `timeout`; throws on failure.
    AsebaClient(uint16_t port, Milliseconds timeout);
    ~AsebaClient();
    AsebaClient(const AsebaClient &) = delete;
    AsebaClient &operator=(const AsebaClient &) = delete;

    // Sends one frame with source 0 and the given words as payload.
    void send(uint16_t type, const std::vector<int16_t> &words);

    // The next frame within `timeout`; nullopt on timeout. Throws if the
    // peer closes the connection or announces an oversized payload.
    std::optional<Frame> receive(Milliseconds timeout);

    // The first frame that satisfies `wanted` within `timeout`; the frames
    // skipped on the way are kept in skipped().
    std::optional<Frame> receive_until(const std::function<bool(const Frame &)> &wanted,
                                       Milliseconds timeout);

    // Every frame that arrives during `duration`.
    std::vector<Frame> collect(Milliseconds duration);

    // Frames received but not returned by receive_until, oldest first.
    const std::vector<Frame> &skipped() const
    {
        return skipped_;
    }

    // GET_VARIABLES then the matching VARIABLES answer from `node`.
    std::optional<std::vector<int16_t>> read_variables(uint16_t node,
                                                       uint16_t start,
                                                       uint16_t count,
                                                       Milliseconds timeout);

    // GET_NODE_DESCRIPTION then the whole description of `node`; nullopt if
    // it does not complete in time or a part is malformed.
    std::optional<NodeDescription> describe(uint16_t node, Milliseconds timeout);

    // The whole description of `node`, requested by someone else; nullopt if
    // it does not complete in time or a part is malformed.
    std::optional<NodeDescription> receive_description(uint16_t node, Milliseconds timeout);

  private:
    int socket_ = -1;
    std::vector<uint8_t> pending_;
    std::vector<Frame> skipped_;
};

} // namespace interop

#endif
