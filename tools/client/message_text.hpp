// Received messages as text for people: what a monitor prints, with node
// labels, event names from the loaded program's global events, and the source
// line of a pc when the node's program is known.

#pragma once

#include <string>

#include "network.hpp"

namespace aseba::client
{

// `message` in one line, e.g. "event pong(30, 7)" or "DIVISION_BY_ZERO at pc
// 14 (line 3: x = x / 0)". `definitions` (may be null) names global events,
// `program` (may be null) gives source lines.
std::string message_text(const Message &message,
                         const CommonDefinitions *definitions,
                         const CompiledProgram *program);

// The wall-clock time of a frame as HH:MM:SS.mmm (UTC).
std::string timestamp_text(std::chrono::system_clock::time_point time);

// "event NAME" when `definitions` declares it, else "event ID".
std::string event_name(uint16_t id, const CommonDefinitions *definitions);

} // namespace aseba::client
