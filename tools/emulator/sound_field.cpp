// The sound model of the arena (see sound_field.hpp).

#include "sound_field.hpp"

#include <algorithm>
#include <cmath>

namespace aseba::arena
{
namespace
{

constexpr double pi = 3.14159265358979323846;
// The microphones' bias and the ADC's range (hardware §3.4: a silent
// microphone reads the middle of the range).
constexpr double bias_counts = 2048;
constexpr double adc_maximum = 4095;
// No microphone comes closer to a loudspeaker than this (cm).
constexpr double nearest_distance = 1;

} // namespace

SoundField::SoundField(const std::vector<SoundSource> &sources)
  : sources_(sources)
{
}

void SoundField::hear(double x, double y, std::vector<Hearing> &hearings) const
{
    hearings.clear();
    for (const SoundSource &source : sources_) {
        double distance = std::max(std::hypot(x - source.x, y - source.y), nearest_distance);
        hearings.push_back(
          { distance / speed_of_sound, source.level * SoundSource::reference_distance / distance });
    }
}

uint16_t SoundField::reading(const std::vector<Hearing> &hearings, double seconds) const
{
    double value = bias_counts;
    for (size_t i = 0; i < sources_.size() && i < hearings.size(); i++) {
        const SoundSource &source = sources_[i];
        double emitted = seconds - hearings[i].delay;
        if (!source.sounding(emitted))
            continue;
        // The tone's phase counts from its start, so that every run begins
        // alike; in turns, less whole turns, so that sin stays quick.
        double turns = source.frequency * (emitted - source.start);
        value += hearings[i].amplitude * std::sin(2 * pi * (turns - std::floor(turns)));
    }
    return uint16_t(std::clamp(std::round(value), 0.0, adc_maximum));
}

} // namespace aseba::arena
