// The status line of a simulated network.

#include "network_status.hpp"

#include <cstdio>

extern "C" {
#include "vm/node_protocol.h"
}

namespace aseba::host
{

namespace
{
// Distinct first-argument values shown per event before the rest is elided.
constexpr size_t shown_argument_values = 6;
} // namespace

NetworkStatus::NetworkStatus(std::vector<GlobalEvent> events)
  : events_(std::move(events))
{
}

void NetworkStatus::count(FrameView frame)
{
    const uint8_t *bytes = frame.bytes;
    frames_++;
    if (frame.size < NODE_HEADER_SIZE)
        return;
    uint16_t type = uint16_t(bytes[4] | (bytes[5] << 8));
    if (type >= NODE_FIRST_SYSTEM_TYPE)
        return;
    event_counts_[type]++;
    if (frame.size >= NODE_HEADER_SIZE + 2) {
        auto argument = int16_t(uint16_t(bytes[6] | (bytes[7] << 8)));
        first_argument_counts_[type][argument]++;
    }
}

std::string NetworkStatus::line(double seconds, size_t robots, size_t clients)
{
    double interval = seconds - seconds_at_last_line_;
    double rate = interval > 0 ? double(frames_ - frames_at_last_line_) / interval : 0;
    frames_at_last_line_ = frames_;
    seconds_at_last_line_ = seconds;

    char head[160];
    std::snprintf(head,
                  sizeof head,
                  "%7.1f s | %zu robot%s | %zu tool%s | %6.0f frames/s",
                  seconds,
                  robots,
                  robots == 1 ? "" : "s",
                  clients,
                  clients == 1 ? "" : "s",
                  rate);
    std::string text = head;
    for (const auto &[type, total] : event_counts_) {
        std::string name =
          type < events_.size() ? events_[type].name : "event " + std::to_string(type);
        text += " | " + name + " " + std::to_string(total);
        const auto &by_argument = first_argument_counts_[type];
        if (by_argument.empty())
            continue;
        text += " (";
        size_t shown = 0;
        for (const auto &[argument, count] : by_argument) {
            if (shown == shown_argument_values) {
                text += " ...";
                break;
            }
            text += (shown++ ? " " : "") + std::to_string(argument) + ":" + std::to_string(count);
        }
        text += ")";
    }
    return text;
}

} // namespace aseba::host
