// The battery (hardware §3.12). Boards before revision 1.3, which the
// firmware targets (AN7 is the accelerometer's Z there), only tell whether
// the battery is above 3.4 V.

#ifndef EPUCK_BATTERY_H
#define EPUCK_BATTERY_H

#include <stdbool.h>

#include "robots/epuck/epuck_board.h"

// Whether the battery is above 3.4 V (the BATT_LOW line is high).
bool epuck_battery_ok(hal_board *board);

#endif
