// The hardware abstraction layer: everything the firmware may ask of a board.
//
// Drivers and the firmware are written once against these functions; the
// dsPIC implementation (hal/dspic30) reaches the chip's registers, the host
// implementation (hal/host) simulates a board on a PC. A board is an
// instance: the host holds many, the dsPIC build exactly one.
//
// Callbacks given to the timer, ADC-scan and edge functions run in interrupt
// context on the chip (and from the host's scheduler on a PC): keep them
// short, and guard data they share with the main loop with
// hal_critical_enter/hal_critical_leave.

#ifndef HAL_H
#define HAL_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/dspic30/dspic30_config.h"

// Defined by each implementation.
typedef struct hal_board hal_board;

// --- clock -------------------------------------------------------------------

// Milliseconds since the board started; wraps after 49 days.
uint32_t hal_milliseconds(hal_board *board);

// Waits about `microseconds` without giving up the processor (short waits such
// as a camera reset pulse; the host does not wait at all).
void hal_delay_microseconds(hal_board *board, uint16_t microseconds);

// --- the communication link (the e-puck's Bluetooth UART1, 115200 8N1) ------

// Takes up to `capacity` bytes received on the communication link (the
// e-puck's Bluetooth UART) without waiting; returns how many.
uint16_t hal_link_receive(hal_board *board, uint8_t *bytes, uint16_t capacity);

// Sends `count` bytes on the communication link, in order.
void hal_link_send(hal_board *board, const uint8_t *bytes, uint16_t count);

// The size of the receive ring: the link keeps at least one whole 522-byte
// frame (hardware §6.5, protocol.md) until the firmware reads it.
#define HAL_LINK_RECEIVE_CAPACITY DSPIC30_LINK_RECEIVE_CAPACITY

// --- periodic timers ---------------------------------------------------------

// The timers a driver may use; each has one callback. The library's use
// (hardware §3.13) is a hint, not a rule.
typedef enum hal_timer {
    HAL_TIMER_AGENDA,      // fast tick for the IR pulses, RC5 sampling, ...
    HAL_TIMER_MOTOR_LEFT,  // left stepper phases
    HAL_TIMER_MOTOR_RIGHT, // right stepper phases
    HAL_TIMER_SPARE,
    HAL_TIMER_COUNT
} hal_timer;

typedef void (*hal_callback)(void *context);

// Calls `callback(context)` every `period_microseconds` (HAL_TIMER_MIN_PERIOD_US
// up to HAL_TIMER_MAX_PERIOD_US, rounded to the timer's resolution) until
// stopped, replacing what the timer did before; returns false, changing
// nothing, for a period out of range.
bool hal_timer_start(hal_board *board,
                     hal_timer timer,
                     uint32_t period_microseconds,
                     hal_callback callback,
                     void *context);

// Stops the timer; its callback is not called again.
void hal_timer_stop(hal_board *board, hal_timer timer);

#define HAL_TIMER_MIN_PERIOD_US DSPIC30_TIMER_MIN_PERIOD_US
#define HAL_TIMER_MAX_PERIOD_US DSPIC30_TIMER_MAX_PERIOD_US

// --- analog inputs (12-bit ADC, AN0..AN15) -------------------------------------

// The analog inputs of the e-puck (hardware §2.3, §3.1).
#define HAL_ADC_MICROPHONE_0    2 // AN2..AN4: microphones 0, 1, 2
#define HAL_ADC_ACCELEROMETER_X 5 // AN5..AN7: accelerometer X, Y, Z
#define HAL_ADC_ACCELEROMETER_Y 6
#define HAL_ADC_ACCELEROMETER_Z 7
#define HAL_ADC_BATTERY         7 // on hardware revision 1.3 only, instead of Z
#define HAL_ADC_PROXIMITY_0     8 // AN8..AN15: proximity phototransistors IR0..IR7
#define HAL_ADC_CHANNEL_COUNT   16
#define HAL_ADC_MAX_VALUE       4095

// Converts analog input `channel` once and returns 0..4095 (waits some tens
// of microseconds); returns 0 for a channel out of range or while a scan runs.
uint16_t hal_adc_read(hal_board *board, uint8_t channel);

// Receives one scan: the values of the scanned channels, lowest channel first.
typedef void (*hal_adc_scan_callback)(void *context, const uint16_t *values, uint8_t count);

// Converts the channels set in `channel_mask` (bit n = ANn, from
// HAL_ADC_SCAN_MIN_CHANNELS to HAL_ADC_SCAN_MAX_CHANNELS of them) over and
// over and hands each finished scan to `callback`, exactly
// HAL_ADC_SCAN_RATE_HZ times a second; returns false, starting nothing, for
// an unsupported mask.
bool hal_adc_scan_start(hal_board *board,
                        uint16_t channel_mask,
                        hal_adc_scan_callback callback,
                        void *context);

// Makes the scans after the current one convert `channel_mask` instead
// (callable from the scan callback); returns false, changing nothing, for an
// unsupported mask.
bool hal_adc_scan_select(hal_board *board, uint16_t channel_mask);

// Stops scanning; the callback is not called again.
void hal_adc_scan_stop(hal_board *board);

#define HAL_ADC_SCAN_RATE_HZ      DSPIC30_ADC_SCAN_RATE_HZ
#define HAL_ADC_SCAN_MIN_CHANNELS DSPIC30_ADC_SCAN_MIN_CHANNELS
#define HAL_ADC_SCAN_MAX_CHANNELS DSPIC30_ADC_SCAN_MAX_CHANNELS

// --- I2C master (camera, extensions) -------------------------------------------

// The camera's 8-bit I2C write address (hardware §3.5); reads use it + 1.
#define HAL_I2C_CAMERA_ADDRESS 0xDC

// Writes `count` bytes to registers `reg`, `reg`+1... of the device at 8-bit
// write address `device`; returns false when the device does not acknowledge
// or the bus fails.
bool hal_i2c_write(hal_board *board,
                   uint8_t device,
                   uint8_t reg,
                   const uint8_t *bytes,
                   uint16_t count);

// Reads `count` bytes from registers `reg`, `reg`+1... of the device at 8-bit
// write address `device`; returns false (bytes undefined) on a failure.
bool hal_i2c_read(hal_board *board, uint8_t device, uint8_t reg, uint8_t *bytes, uint16_t count);

// --- digital pins (hardware §3.1) -------------------------------------------------

// Outputs come first; the inputs start at HAL_PIN_FIRST_INPUT.
typedef enum hal_pin {
    HAL_PIN_LED_0, // ring LEDs 0 (front) .. 7, clockwise, active high
    HAL_PIN_LED_1,
    HAL_PIN_LED_2,
    HAL_PIN_LED_3,
    HAL_PIN_LED_4,
    HAL_PIN_LED_5,
    HAL_PIN_LED_6,
    HAL_PIN_LED_7,
    HAL_PIN_FRONT_LED,    // red, high power
    HAL_PIN_BODY_LED,     // green, diffuse
    HAL_PIN_MOTOR_LEFT_A, // stepper phases A..D, left then right motor
    HAL_PIN_MOTOR_LEFT_B,
    HAL_PIN_MOTOR_LEFT_C,
    HAL_PIN_MOTOR_LEFT_D,
    HAL_PIN_MOTOR_RIGHT_A,
    HAL_PIN_MOTOR_RIGHT_B,
    HAL_PIN_MOTOR_RIGHT_C,
    HAL_PIN_MOTOR_RIGHT_D,
    HAL_PIN_IR_PULSE_0_4, // proximity emitters, one line per sensor pair
    HAL_PIN_IR_PULSE_1_5,
    HAL_PIN_IR_PULSE_2_6,
    HAL_PIN_IR_PULSE_3_7,
    HAL_PIN_CAMERA_RESET, // active low
    HAL_PIN_AUDIO_ON,     // speaker and codec power
    HAL_PIN_SELECTOR_0,   // inputs: selector bits 0..3
    HAL_PIN_SELECTOR_1,
    HAL_PIN_SELECTOR_2,
    HAL_PIN_SELECTOR_3,
    HAL_PIN_BATTERY_LOW, // input, low when the battery is below 3.4 V
    HAL_PIN_REMOTE,      // input, the RC5 receiver, idles high
    HAL_PIN_CAMERA_HREF, // inputs from the camera
    HAL_PIN_CAMERA_VSYNC,
    HAL_PIN_CAMERA_PCLK,
    HAL_PIN_COUNT
} hal_pin;

#define HAL_PIN_FIRST_INPUT HAL_PIN_SELECTOR_0

// Drives output `pin` high (true) or low; does nothing for an input.
void hal_pin_write(hal_board *board, hal_pin pin, bool high);

// The level of `pin`: what an input sees, or what an output drives.
bool hal_pin_read(hal_board *board, hal_pin pin);

// Calls `callback(context)` on each falling edge of input `pin` until
// unwatched; returns false when the pin cannot signal edges (only
// HAL_PIN_REMOTE can: INT0).
bool hal_pin_watch_falling_edge(hal_board *board,
                                hal_pin pin,
                                hal_callback callback,
                                void *context);

// Stops signalling edges of `pin`.
void hal_pin_unwatch(hal_board *board, hal_pin pin);

// --- camera pixel port (data on RD8..RD15, hardware §3.5) -----------------------

// Waits for the next frame and stores the first `count` bytes the camera
// sends on its row `row` (0 = first row of the configured window) into
// `bytes`; returns false when the camera sends no frame in time. Blocks up to
// one frame time.
bool hal_camera_read_row(hal_board *board, uint16_t row, uint8_t *bytes, uint16_t count);

// --- data EEPROM (2048 words of 16 bits) ------------------------------------------

#define HAL_EEPROM_WORDS  DSPIC30_EEPROM_WORDS
#define HAL_EEPROM_ERASED 0xFFFFu

// The word at `index` (0..HAL_EEPROM_WORDS-1); HAL_EEPROM_ERASED out of range.
uint16_t hal_eeprom_read(hal_board *board, uint16_t index);

// Erases the word at `index` to HAL_EEPROM_ERASED; returns false on failure.
bool hal_eeprom_erase_word(hal_board *board, uint16_t index);

// Programs the word at `index`: bits can only go from 1 to 0, so the word
// must have been erased to hold `value`; returns false on failure.
bool hal_eeprom_write_word(hal_board *board, uint16_t index, uint16_t value);

// --- program flash (24-bit instructions in rows of 32) ---------------------------

// Addresses are program-counter addresses: 2 per instruction (hardware §1.2).
#define HAL_FLASH_ROW_INSTRUCTIONS DSPIC30_FLASH_ROW_INSTRUCTIONS
#define HAL_FLASH_ROW_SPAN         DSPIC30_FLASH_ROW_SPAN // PC units per row
#define HAL_FLASH_END              DSPIC30_FLASH_END      // first address after flash
#define HAL_FLASH_ERASED           0xFFFFFFul

// The 24-bit instruction at even address `address`; 0 out of range.
uint32_t hal_flash_read(hal_board *board, uint32_t address);

// Erases the row starting at `row_address` (a multiple of HAL_FLASH_ROW_SPAN)
// to HAL_FLASH_ERASED; returns false for a bad address or a failure.
bool hal_flash_erase_row(hal_board *board, uint32_t row_address);

// Programs the row at `row_address` with HAL_FLASH_ROW_INSTRUCTIONS 24-bit
// instructions; bits only go from 1 to 0, so erase the row first. Returns
// false for a bad address or a failure.
bool hal_flash_write_row(hal_board *board, uint32_t row_address, const uint32_t *instructions);

// --- interrupts, reset, idle --------------------------------------------------------

typedef uint16_t hal_critical_state;

// Holds off every interrupt-context callback until the matching leave;
// returns what hal_critical_leave restores (sections nest).
hal_critical_state hal_critical_enter(hal_board *board);

// Ends the critical section begun by the hal_critical_enter that returned
// `state`.
void hal_critical_leave(hal_board *board, hal_critical_state state);

// Restarts the board (on the e-puck this enters the bootloader first). The
// chip never returns; the host records the request and returns.
void hal_reset(hal_board *board);

// Sleeps until something may have happened (an interrupt on the chip; the
// host scheduler decides). Returns at once when nothing can wait.
void hal_idle(hal_board *board);

#endif
