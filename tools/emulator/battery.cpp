// The battery model (see battery.hpp).

#include "battery.hpp"

#include <algorithm>
#include <array>

namespace aseba::arena
{
namespace
{

struct CurvePoint {
    double charge;
    double volts;
};

// Points of the discharge curve, from empty to full; linear between them.
constexpr std::array<CurvePoint, 6> discharge_curve = { {
  { 0.00, 3.00 },
  { 0.05, 3.40 },
  { 0.10, 3.60 },
  { 0.20, 3.70 },
  { 0.90, 4.05 },
  { 1.00, 4.20 },
} };

constexpr double seconds_per_hour = 3600;

} // namespace

double battery_volts(double charge)
{
    charge = std::clamp(charge, 0.0, 1.0);
    for (size_t i = 1; i < discharge_curve.size(); i++) {
        const CurvePoint &low = discharge_curve[i - 1], &high = discharge_curve[i];
        if (charge <= high.charge)
            return low.volts +
                   (charge - low.charge) * (high.volts - low.volts) / (high.charge - low.charge);
    }
    return discharge_curve.back().volts;
}

Battery::Battery(const BatteryModel &model, double charge)
  : model_(model)
  , charge_(charge)
  , low_(volts() < battery_low_volts)
{
}

void Battery::drain(double seconds, unsigned motors_turning)
{
    double milliamps = model_.idle_ma + model_.motor_ma * motors_turning;
    double used_mah = milliamps * seconds / seconds_per_hour;
    charge_ = std::max(0.0, charge_ - used_mah / model_.capacity_mah);
    low_ = volts() < battery_low_volts;
}

} // namespace aseba::arena
