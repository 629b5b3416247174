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

double SoundField::pressure(double x, double y, double seconds) const
{
    double sum = 0;
    for (const SoundSource &source : sources_) {
        double distance = std::max(std::hypot(x - source.x, y - source.y), nearest_distance);
        double emitted = seconds - distance / speed_of_sound;
        if (!source.sounding(emitted))
            continue;
        double amplitude = source.level * SoundSource::reference_distance / distance;
        // The tone's phase counts from its start, so that every beep of a
        // source and every run begin alike.
        sum += amplitude * std::sin(2 * pi * source.frequency * (emitted - source.start));
    }
    return sum;
}

uint16_t SoundField::reading(double x, double y, double seconds) const
{
    double value = bias_counts + pressure(x, y, seconds);
    return uint16_t(std::clamp(std::round(value), 0.0, adc_maximum));
}

} // namespace aseba::arena
