// The messages of Aseba protocol 5 (protocol.md §3-§6) as C++ values, and
// their exact payload layouts. Every message of the table can be encoded and
// decoded, in both directions, so that a monitor can show what other hosts
// send too. Decoding is strict like upstream hosts: a payload that does not
// match its layout exactly is rejected with ProtocolError.

#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "tools/compiler/target.hpp"
#include "wire.hpp"

extern "C" {
#include "vm/node_protocol.h"
}

namespace aseba::client
{

// Bootloader message types (protocol.md §3, §6.9); the node-side header has
// no use for them.
constexpr uint16_t MSG_BOOTLOADER_RESET = 0x8000;
constexpr uint16_t MSG_BOOTLOADER_READ_PAGE = 0x8001;
constexpr uint16_t MSG_BOOTLOADER_WRITE_PAGE = 0x8002;
constexpr uint16_t MSG_BOOTLOADER_PAGE_DATA_WRITE = 0x8003;
constexpr uint16_t MSG_BOOTLOADER_DESCRIPTION = 0x8004;
constexpr uint16_t MSG_BOOTLOADER_PAGE_DATA_READ = 0x8005;
constexpr uint16_t MSG_BOOTLOADER_ACK = 0x8006;
constexpr uint16_t MSG_INVALID = 0xFFFF;
constexpr uint16_t BOOTLOADER_ERROR_PROGRAMMING_FAILED = 2; // the one code with an address
constexpr size_t BOOTLOADER_DATA_CHUNK = 4;

constexpr uint16_t FIRST_SYSTEM_TYPE = NODE_FIRST_SYSTEM_TYPE; // below: user events
constexpr uint16_t PROTOCOL_VERSION = NODE_PROTOCOL_VERSION;
constexpr uint16_t MIN_PROTOCOL_VERSION = 4; // oldest node hosts accept (§1)
using aseba::MAX_EVENT_WORDS;                // the compiler's, which is the payload's:
static_assert(MAX_EVENT_WORDS == MAX_PAYLOAD_SIZE / 2);
constexpr size_t MAX_VARIABLES_WORDS = NODE_MAX_VARIABLES_WORDS; // one VARIABLES answer
constexpr size_t MAX_BYTECODE_CHUNK_WORDS = 256;                 // one SET_BYTECODE
constexpr size_t MAX_SET_VARIABLES_WORDS = 256;                  // one SET_VARIABLES

// Execution flags of EXECUTION_STATE_CHANGED (bytecode.md §6).
constexpr uint16_t FLAG_EVENT_ACTIVE = 0x0001;
constexpr uint16_t FLAG_STEP_BY_STEP = 0x0002;
constexpr uint16_t FLAG_EVENT_RUNNING = 0x0004;

// --- node to host ----------------------------------------------------------

// A global event (type below 0x8000), from a node or from a host.
struct UserEvent {
    uint16_t id = 0;
    std::vector<int16_t> arguments;
};
struct Description {
    std::string name;
    uint16_t protocol_version = 0;
    uint16_t bytecode_size = 0;
    uint16_t stack_size = 0;
    uint16_t variables_size = 0;
    uint16_t named_variables_count = 0;
    uint16_t local_events_count = 0;
    uint16_t native_functions_count = 0;
};
struct NamedVariableDescription {
    NamedVariable variable;
};
struct LocalEventDescription {
    LocalEvent event;
};
struct NativeFunctionDescription {
    NativeFunction function;
};
struct Disconnected {
};
struct Variables {
    uint16_t start = 0;
    std::vector<int16_t> values;
};
struct ArrayAccessOutOfBounds {
    uint16_t pc = 0;
    uint16_t size = 0;
    uint16_t index = 0;
};
struct DivisionByZero {
    uint16_t pc = 0;
};
struct EventExecutionKilled {
    uint16_t pc = 0;
};
struct NodeSpecificError {
    uint16_t pc = 0;
    std::string message;
};
struct ExecutionStateChanged {
    uint16_t pc = 0;
    uint16_t flags = 0;
};
struct BreakpointSetResult {
    uint16_t pc = 0;
    uint16_t success = 0;
};
struct NodePresent {
    uint16_t version = 0;
};
struct BootloaderDescription {
    uint16_t page_size = 0;
    uint16_t pages_start = 0;
    uint16_t pages_count = 0;
};
struct BootloaderPageDataRead {
    std::array<uint8_t, BOOTLOADER_DATA_CHUNK> data{};
};
struct BootloaderAck {
    uint16_t error_code = 0;
    std::optional<uint16_t> error_address; // only with PROGRAMMING_FAILED
};

// --- host to node ----------------------------------------------------------

// The two broadcasts: GET_DESCRIPTION and LIST_NODES.
struct GetDescription {
    uint16_t version = PROTOCOL_VERSION;
};
struct ListNodes {
    uint16_t version = PROTOCOL_VERSION;
};
// An addressed command whose payload is only `dest`: RESET, RUN, PAUSE, STEP,
// STOP, GET_EXECUTION_STATE, BREAKPOINT_CLEAR_ALL, WRITE_BYTECODE, REBOOT,
// SUSPEND_TO_RAM, BOOTLOADER_RESET.
struct NodeCommand {
    uint16_t type = 0;
    uint16_t dest = 0;
};
struct SetBytecode {
    uint16_t dest = 0;
    uint16_t start = 0;
    std::vector<uint16_t> words;
};
// BREAKPOINT_SET or BREAKPOINT_CLEAR.
struct BreakpointCommand {
    uint16_t type = 0;
    uint16_t dest = 0;
    uint16_t pc = 0;
};
struct GetVariables {
    uint16_t dest = 0;
    uint16_t start = 0;
    uint16_t length = 0;
};
struct SetVariables {
    uint16_t dest = 0;
    uint16_t start = 0;
    std::vector<int16_t> values;
};
struct GetNodeDescription {
    uint16_t dest = 0;
    uint16_t version = PROTOCOL_VERSION;
};
// BOOTLOADER_READ_PAGE or BOOTLOADER_WRITE_PAGE.
struct BootloaderPageCommand {
    uint16_t type = 0;
    uint16_t dest = 0;
    uint16_t page = 0;
};
struct BootloaderPageDataWrite {
    uint16_t dest = 0;
    std::array<uint8_t, BOOTLOADER_DATA_CHUNK> data{};
};

using Message = std::variant<UserEvent,
                             Description,
                             NamedVariableDescription,
                             LocalEventDescription,
                             NativeFunctionDescription,
                             Disconnected,
                             Variables,
                             ArrayAccessOutOfBounds,
                             DivisionByZero,
                             EventExecutionKilled,
                             NodeSpecificError,
                             ExecutionStateChanged,
                             BreakpointSetResult,
                             NodePresent,
                             BootloaderDescription,
                             BootloaderPageDataRead,
                             BootloaderAck,
                             GetDescription,
                             ListNodes,
                             NodeCommand,
                             SetBytecode,
                             BreakpointCommand,
                             GetVariables,
                             SetVariables,
                             GetNodeDescription,
                             BootloaderPageCommand,
                             BootloaderPageDataWrite>;

// The frame type of `message`.
uint16_t message_type(const Message &message);

// The frame carrying `message` from `source` (0 for hosts). Throws
// ProtocolError if it cannot be sent as is: payload or string too long, or a
// type that does not fit the struct (e.g. NodeCommand with RUN's type is fine,
// with SET_BYTECODE's it is not).
Frame encode(const Message &message, uint16_t source = HOST_SOURCE);

// The message a frame carries; throws ProtocolError if its type is unknown or
// reserved, or its payload does not match the type's layout exactly.
Message decode(const Frame &frame);

// The protocol's name of a message type ("LIST_NODES", "user event 3", ...).
std::string message_type_name(uint16_t type);

} // namespace aseba::client
