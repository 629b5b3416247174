// A simulated e-puck's battery: one Li-ion cell, its charge drained by the
// current the robot draws (a constant part, and each motor whose coils are
// powered), its voltage read from the charge on a discharge curve, and the
// board's BATT_LOW line low below 3.4 V as on the robot (hardware §3.12).
// The numbers are in docs/arena-format.md.

#pragma once

#include "arena_file.hpp"

namespace aseba::arena
{

// The BATT_LOW comparator's threshold (hardware §3.12).
constexpr double battery_low_volts = 3.4;

// The cell's voltage at rest at `charge` (0: empty, 1: full), on a typical
// Li-ion discharge curve: 4.2 V full, a slow slope through the middle, the
// knee below 10 %, 3.4 V at 5 %, 3.0 V empty.
double battery_volts(double charge);

class Battery
{
  public:
    Battery(const BatteryModel &model, double charge);

    // Draws the model's current for `seconds` with `motors_turning` motors
    // (0 to 2) powered.
    void drain(double seconds, unsigned motors_turning);

    // The charge left, 0..1 of the capacity.
    double charge() const
    {
        return charge_;
    }
    double volts() const
    {
        return battery_volts(charge_);
    }
    // Whether BATT_LOW reads low (the firmware reads the line thousands of
    // times a second; the charge changes at each drain).
    bool low() const
    {
        return low_;
    }

  private:
    BatteryModel model_;
    double charge_;
    bool low_;
};

} // namespace aseba::arena
