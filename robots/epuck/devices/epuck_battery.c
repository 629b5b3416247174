// The battery-low line is active low (§3.1, §3.12).

#include "epuck_battery.h"

bool epuck_battery_ok(hal_board *board)
{
    return epuck_board_pin_read(board, EPUCK_PIN_BATTERY_LOW);
}
