// The JSON payloads of the bridge's topics (docs/mqtt.md), written and read.
// Reading is strict: whatever comes from the broker is checked whole before
// anything reaches a robot, and a payload that does not fit gets a
// PayloadError whose what() is a sentence for the log.

#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "tools/client/network.hpp"

namespace aseba::mqtt
{

class PayloadError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

// Where an event was emitted, as the bridge that published it tells.
struct EventOrigin {
    std::string bridge;    // that bridge's session: random, new at each start
    uint64_t sequence = 0; // counts that session's events from 1
    std::string network;
    uint16_t node = 0; // the emitter's id on its network; 0 for a host tool
};

// An event as published on PREFIX/event/NAME.
struct EventPayload {
    std::vector<int16_t> arguments;
    std::optional<EventOrigin> origin; // absent when not published by a bridge
};

// {"args":[...],"network":...,"node":...,"node_name":...,"time_ms":...,
//  "bridge":...,"seq":...}
std::string write_event(const std::vector<int16_t> &arguments,
                        const EventOrigin &origin,
                        const std::string &node_name,
                        int64_t time_ms);

// Reads an event: an object with "args" (integers from -32768 to 32767;
// optional), a bare array of them, or an empty payload (no arguments).
// More than `max_arguments` arguments is an error.
EventPayload read_event(std::string_view payload, size_t max_arguments);

// A node's presence: its description and execution state.
std::string write_node(const std::string &network, const client::Node &node);

// {"online":true|false,"bridge":SESSION,"networks":[...]} for the status topic.
std::string write_status(bool online,
                         const std::string &bridge,
                         const std::vector<std::string> &networks);

// A watched variable's values.
std::string write_values(const std::vector<int16_t> &values);

enum class CommandKind { load, run, pause, stop, reset, reboot };

struct Command {
    CommandKind kind = CommandKind::run;
    std::string program; // load: the text of an .aesl project or a script
    std::string request; // the request's "request" field as JSON, echoed in the reply
};

// {"command":"run"|"pause"|"stop"|"reset"|"reboot"|"load", "program":TEXT
//  (load only), "request":ANY (optional)}.
Command read_command(std::string_view payload);

// The reply to a command, on the node's reply topic.
struct Reply {
    std::string command; // as asked (empty if unreadable)
    std::string request; // JSON, echoed (empty: none)
    uint16_t node = 0;
    bool ok = false;
    std::string state; // "running", "stopped", ... when known
    std::string error;
};
std::string write_reply(const Reply &reply);

// The name of a command kind, as in payloads.
const char *command_name(CommandKind kind);

} // namespace aseba::mqtt
