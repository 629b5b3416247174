// What the e-pucks' microphones hear of the arena's sound sources: each
// source a point in the plane playing a tone, heard after the time sound
// takes to cover the distance and with an amplitude falling as 1 / distance
// (spreading from a point), the sources adding up; no echo from walls or
// robots, no occlusion (docs/arena-format.md).

#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "arena_file.hpp"

namespace aseba::arena
{

// cm/s, in air at 20 °C.
constexpr double speed_of_sound = 34300;

// Where a microphone sits on the robot (cm, robot frame: forward, left).
struct MicrophonePlace {
    double forward;
    double left;
};

// The e-puck's three microphones in the firmware's order (AN2, AN3, AN4).
// ⚠ Their places are not in the sources the hardware fact sheet read
// (§3.4): these are the e-puck2's right, left and back microphones
// (GCtronic's board coordinates), which keep the e-puck's numbering.
constexpr std::array<MicrophonePlace, 3> microphone_places = { {
  { 0.835, -3.03 }, // 0: right
  { 0.835, 3.03 },  // 1: left
  { -2.305, 0 },    // 2: back
} };

// How a place hears one source: how late, and how loud.
struct Hearing {
    double delay;     // seconds: distance / speed_of_sound
    double amplitude; // ADC counts: the source's level × reference distance / distance
};

class SoundField
{
  public:
    explicit SoundField(const std::vector<SoundSource> &sources);

    bool silent() const
    {
        return sources_.empty();
    }

    // How (x, y) hears each source, in the sources' order, into `hearings`
    // (a microphone moves only between world steps, while it is read
    // thousands of times a second). Distances below 1 cm, the closest a
    // microphone gets to a loudspeaker, count as 1 cm.
    void hear(double x, double y, std::vector<Hearing> &hearings) const;

    // What a microphone hearing the sources so converts to at `seconds`: the
    // bias (the middle of the 12-bit range) plus each source's tone as it
    // left the source `delay` earlier, times its amplitude; rounded and
    // clipped to the ADC's range.
    uint16_t reading(const std::vector<Hearing> &hearings, double seconds) const;

  private:
    std::vector<SoundSource> sources_;
};

} // namespace aseba::arena
