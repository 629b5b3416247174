// LEDs, selector and battery line (hardware §3.7, §3.8, §3.12) on the host
// board, seen through the modelled world's pins.

#include "modelled_world.hpp"

#include <gtest/gtest.h>

#include <memory>

extern "C" {
#include "robots/epuck/devices/epuck_battery.h"
#include "robots/epuck/devices/epuck_leds.h"
#include "robots/epuck/devices/epuck_selector.h"
}

namespace drivers_test
{
namespace
{

struct BoardIo : ::testing::Test {
    std::unique_ptr<hal_board> board = std::make_unique<hal_board>();
    ModelledWorld world;
    void SetUp() override
    {
        host_board_init(board.get(), nullptr, nullptr);
        world.attach(board.get());
    }
};

TEST_F(BoardIo, EachLedDrivesItsOwnPinActiveHigh)
{
    epuck_leds leds{};
    epuck_leds_init(&leds, board.get());
    // The pins of §3.7: ring LEDs 0..7, then body and front.
    const std::array<std::pair<uint16_t, epuck_pin>, 10> wiring = { {
      { 0, EPUCK_PIN_LED_0 },
      { 1, EPUCK_PIN_LED_1 },
      { 2, EPUCK_PIN_LED_2 },
      { 3, EPUCK_PIN_LED_3 },
      { 4, EPUCK_PIN_LED_4 },
      { 5, EPUCK_PIN_LED_5 },
      { 6, EPUCK_PIN_LED_6 },
      { 7, EPUCK_PIN_LED_7 },
      { EPUCK_LED_BODY, EPUCK_PIN_BODY_LED },
      { EPUCK_LED_FRONT, EPUCK_PIN_FRONT_LED },
    } };
    for (auto [led, pin] : wiring) {
        SCOPED_TRACE("led " + std::to_string(led));
        EXPECT_FALSE(world.output[pin]);
        epuck_leds_set(&leds, led, true);
        EXPECT_TRUE(world.output[pin]);
        EXPECT_TRUE(epuck_leds_get(&leds, led));
        for (auto [other, other_pin] : wiring) {
            if (other != led) {
                EXPECT_FALSE(world.output[other_pin]) << "led " << other;
            }
        }
        epuck_leds_set(&leds, led, false);
        EXPECT_FALSE(world.output[pin]);
    }
    // Unchanged states do not touch the pins; numbers out of range are ignored.
    world.changes.clear();
    epuck_leds_set(&leds, 3, false);
    epuck_leds_set(&leds, EPUCK_LED_COUNT, true);
    EXPECT_TRUE(world.changes.empty());
}

// Selector bit n is pin RG(6+n), read as it is (§3.8).
TEST_F(BoardIo, SelectorReadsItsFourBits)
{
    for (unsigned position = 0; position < 16; position++) {
        for (unsigned bit = 0; bit < 4; bit++)
            world.input[EPUCK_PIN_SELECTOR_0 + bit] = (position >> bit) & 1u;
        EXPECT_EQ(epuck_selector_read(board.get()), position);
    }
}

TEST_F(BoardIo, BatteryIsOkWhileTheLowLineIsHigh)
{
    world.input[EPUCK_PIN_BATTERY_LOW] = true;
    EXPECT_TRUE(epuck_battery_ok(board.get()));
    world.input[EPUCK_PIN_BATTERY_LOW] = false;
    EXPECT_FALSE(epuck_battery_ok(board.get()));
}

} // namespace
} // namespace drivers_test
