// The live status line of a simulated network: time, traffic, and the user
// events the robots emitted, by name (and by first argument, which is how a
// swarm controller such as the paper's says which colour raised an alarm).

#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "network.hpp"
#include "tools/compiler/target.hpp"

namespace aseba::host
{

class NetworkStatus
{
  public:
    // Event names come from the loaded program's definitions (may be empty).
    explicit NetworkStatus(std::vector<GlobalEvent> events);

    // Counts one frame that crossed the network.
    void count(FrameView frame);

    // One line: `seconds` since the start, robots, tools connected, frames
    // per second since the previous line, and the events seen so far.
    std::string line(double seconds, size_t robots, size_t clients);

  private:
    std::vector<GlobalEvent> events_;
    std::map<uint16_t, uint64_t> event_counts_;
    std::map<uint16_t, std::map<int16_t, uint64_t>> first_argument_counts_;
    uint64_t frames_ = 0;
    uint64_t frames_at_last_line_ = 0;
    double seconds_at_last_line_ = 0;
};

} // namespace aseba::host
