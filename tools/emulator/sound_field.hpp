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

class SoundField
{
  public:
    explicit SoundField(const std::vector<SoundSource> &sources);

    bool silent() const
    {
        return sources_.empty();
    }

    // The sound pressure at (x, y) at time `seconds`, in ADC counts about the
    // microphones' bias: each source's tone as it left the source
    // distance / speed_of_sound earlier, scaled by its reference distance
    // over the distance (at least the closest a microphone can get to a
    // loudspeaker, 1 cm).
    double pressure(double x, double y, double seconds) const;

    // What a microphone at (x, y) converts to at `seconds`: the bias (the
    // middle of the 12-bit range) plus the pressure, rounded and clipped.
    uint16_t reading(double x, double y, double seconds) const;

  private:
    std::vector<SoundSource> sources_;
};

} // namespace aseba::arena
