// The e-puck's board: what the e-puck's drivers need besides hal.h, by the
// names the robot gives them (hardware §2, §3): periodic timers, the analog
// inputs and their scans, the I2C bus, the pins, the camera's pixel port.
//
// A port that carries an e-puck implements it: ports/dspic30 (the robot's
// dsPIC30F6014A, register by register) and boards/epuck_host (the simulated robot,
// answered by a world). Callbacks given to the timer, scan and edge functions
// run in interrupt context on the chip (from the host's scheduler on a PC):
// keep them short, and guard what they share with the main loop with
// hal_critical_enter/hal_critical_leave.

#ifndef EPUCK_BOARD_H
#define EPUCK_BOARD_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/hal.h"

typedef void (*epuck_callback)(void *context);

// --- periodic timers (the library's use, §3.13) --------------------------------------

typedef enum epuck_timer {
    EPUCK_TIMER_MOTOR_LEFT,  // left stepper phases
    EPUCK_TIMER_MOTOR_RIGHT, // right stepper phases
    EPUCK_TIMER_SPARE,       // the remote's RC5 sampling
    EPUCK_TIMER_COUNT
} epuck_timer;

// The periods every e-puck board supports.
#define EPUCK_TIMER_MIN_PERIOD_US 20ul      // shorter would flood the CPU
#define EPUCK_TIMER_MAX_PERIOD_US 1000000ul // one second

// Calls `callback(context)` every `period_microseconds` (EPUCK_TIMER_MIN_PERIOD_US
// up to EPUCK_TIMER_MAX_PERIOD_US, rounded to the timer's resolution) until
// stopped, replacing what the timer did before; returns false, changing
// nothing, for a period out of range.
bool epuck_board_timer_start(hal_board *board,
                             epuck_timer timer,
                             uint32_t period_microseconds,
                             epuck_callback callback,
                             void *context);

// Stops the timer; its callback is not called again.
void epuck_board_timer_stop(hal_board *board, epuck_timer timer);

// --- analog inputs (12-bit ADC, AN0..AN15, §2.3, §3.1) ---------------------------------

#define EPUCK_ADC_MICROPHONE_0    2 // AN2..AN4: microphones 0, 1, 2
#define EPUCK_ADC_ACCELEROMETER_X 5 // AN5..AN7: accelerometer X, Y, Z
#define EPUCK_ADC_ACCELEROMETER_Y 6
#define EPUCK_ADC_ACCELEROMETER_Z 7
#define EPUCK_ADC_BATTERY         7 // on hardware revision 1.3 only, instead of Z
#define EPUCK_ADC_PROXIMITY_0     8 // AN8..AN15: proximity phototransistors IR0..IR7
#define EPUCK_ADC_CHANNEL_COUNT   16
#define EPUCK_ADC_MAX_VALUE       4095

// Scans: every finished scan is handed over EPUCK_ADC_SCAN_RATE_HZ times a
// second (the library's advanced driver), of 2 to 6 channels.
#define EPUCK_ADC_SCAN_RATE_HZ      16384ul
#define EPUCK_ADC_SCAN_MIN_CHANNELS 2u
#define EPUCK_ADC_SCAN_MAX_CHANNELS 6u

// Converts analog input `channel` once and returns 0..4095 (waits some tens
// of microseconds); returns 0 for a channel out of range or while a scan runs.
uint16_t epuck_board_adc_read(hal_board *board, uint8_t channel);

// Receives one scan: the values of the scanned channels, lowest channel first.
typedef void (*epuck_adc_scan_callback)(void *context, const uint16_t *values, uint8_t count);

// Converts the channels set in `channel_mask` (bit n = ANn, from
// EPUCK_ADC_SCAN_MIN_CHANNELS to EPUCK_ADC_SCAN_MAX_CHANNELS of them) over
// and over and hands each finished scan to `callback`, exactly
// EPUCK_ADC_SCAN_RATE_HZ times a second; returns false, starting nothing, for
// an unsupported mask.
bool epuck_board_adc_scan_start(hal_board *board,
                                uint16_t channel_mask,
                                epuck_adc_scan_callback callback,
                                void *context);

// Makes the scans after the current one convert `channel_mask` instead
// (callable from the scan callback); returns false, changing nothing, for an
// unsupported mask.
bool epuck_board_adc_scan_select(hal_board *board, uint16_t channel_mask);

// Stops scanning; the callback is not called again.
void epuck_board_adc_scan_stop(hal_board *board);

// Receives `scans` (2 or more) scans in a row that read the same `values`,
// with no other scan and no input edge between them, and takes the first of
// them, or more: exactly what as many calls of the scan callback would have
// done. Returns how many it took (1..scans); the board hands over the
// others afterwards. The timer callbacks due during the scans taken run
// after it, at their own times: a run callback shares nothing with them,
// and they neither start, stop nor select the scan.
typedef uint16_t (*epuck_adc_scan_run_callback)(void *context,
                                                const uint16_t *values,
                                                uint8_t count,
                                                uint16_t scans);

// Lets the board hand the running scan's stretches of unchanging inputs to
// `callback` at once (NULL: one scan at a time). A simulated board, whose
// 16,384 scans a second are much of its work, does so when its world says
// the inputs hold still (a silent arena's microphones); a chip converts one
// scan at a time and ignores this. Cleared by epuck_board_adc_scan_start and
// epuck_board_adc_scan_stop.
void epuck_board_adc_scan_runs(hal_board *board, epuck_adc_scan_run_callback callback);

// --- I2C master (camera, extensions, §2.4) ------------------------------------------------

// The camera's 8-bit I2C write address (hardware §3.5); reads use it + 1.
#define EPUCK_I2C_CAMERA_ADDRESS 0xDC

// Writes `count` bytes to registers `reg`, `reg`+1... of the device at 8-bit
// write address `device`; returns false when the device does not acknowledge
// or the bus fails.
bool epuck_board_i2c_write(hal_board *board,
                           uint8_t device,
                           uint8_t reg,
                           const uint8_t *bytes,
                           uint16_t count);

// Reads `count` bytes from registers `reg`, `reg`+1... of the device at 8-bit
// write address `device`; returns false (bytes undefined) on a failure.
bool epuck_board_i2c_read(hal_board *board,
                          uint8_t device,
                          uint8_t reg,
                          uint8_t *bytes,
                          uint16_t count);

// --- pins (§3.1) --------------------------------------------------------------------------

// Outputs come first; the inputs start at EPUCK_PIN_FIRST_INPUT.
typedef enum epuck_pin {
    EPUCK_PIN_LED_0, // ring LEDs 0 (front) .. 7, clockwise, active high
    EPUCK_PIN_LED_1,
    EPUCK_PIN_LED_2,
    EPUCK_PIN_LED_3,
    EPUCK_PIN_LED_4,
    EPUCK_PIN_LED_5,
    EPUCK_PIN_LED_6,
    EPUCK_PIN_LED_7,
    EPUCK_PIN_FRONT_LED,    // red, high power
    EPUCK_PIN_BODY_LED,     // green, diffuse
    EPUCK_PIN_MOTOR_LEFT_A, // stepper phases A..D, left then right motor
    EPUCK_PIN_MOTOR_LEFT_B,
    EPUCK_PIN_MOTOR_LEFT_C,
    EPUCK_PIN_MOTOR_LEFT_D,
    EPUCK_PIN_MOTOR_RIGHT_A,
    EPUCK_PIN_MOTOR_RIGHT_B,
    EPUCK_PIN_MOTOR_RIGHT_C,
    EPUCK_PIN_MOTOR_RIGHT_D,
    EPUCK_PIN_IR_PULSE_0_4, // proximity emitters, one line per sensor pair
    EPUCK_PIN_IR_PULSE_1_5,
    EPUCK_PIN_IR_PULSE_2_6,
    EPUCK_PIN_IR_PULSE_3_7,
    EPUCK_PIN_CAMERA_RESET, // active low
    EPUCK_PIN_AUDIO_ON,     // speaker and codec power
    EPUCK_PIN_SELECTOR_0,   // inputs: selector bits 0..3
    EPUCK_PIN_SELECTOR_1,
    EPUCK_PIN_SELECTOR_2,
    EPUCK_PIN_SELECTOR_3,
    EPUCK_PIN_BATTERY_LOW, // input, low when the battery is below 3.4 V
    EPUCK_PIN_REMOTE,      // input, the RC5 receiver, idles high
    EPUCK_PIN_CAMERA_HREF, // inputs from the camera
    EPUCK_PIN_CAMERA_VSYNC,
    EPUCK_PIN_CAMERA_PCLK,
    EPUCK_PIN_COUNT
} epuck_pin;

#define EPUCK_PIN_FIRST_INPUT EPUCK_PIN_SELECTOR_0

// Drives output `pin` high (true) or low; does nothing for an input.
void epuck_board_pin_write(hal_board *board, epuck_pin pin, bool high);

// The level of `pin`: what an input sees, or what an output drives.
bool epuck_board_pin_read(hal_board *board, epuck_pin pin);

// The levels of the `count` pins (1 to 16) from `first` on, pin first + i in
// bit i: what as many calls of epuck_board_pin_read give, in one call (the
// selector's four bits, read at every pass of the main loop).
uint16_t epuck_board_pins_read(hal_board *board, epuck_pin first, uint8_t count);

// Calls `callback(context)` on each falling edge of input `pin` until
// unwatched; returns false when the pin cannot signal edges (only
// EPUCK_PIN_REMOTE can: INT0).
bool epuck_board_pin_watch_falling_edge(hal_board *board,
                                        epuck_pin pin,
                                        epuck_callback callback,
                                        void *context);

// Stops signalling edges of `pin`.
void epuck_board_pin_unwatch(hal_board *board, epuck_pin pin);

// --- the camera's pixel port (data on RD8..RD15, §3.5) ----------------------------------
// A row is read in steps, so that the main loop never waits for a frame:
// start once, then step from each pass of the loop until it is done.

typedef enum epuck_camera_step {
    EPUCK_CAMERA_READING, // not yet: step again later
    EPUCK_CAMERA_DONE,    // the row is in the bytes given at start
    EPUCK_CAMERA_FAILED   // the camera sent no frame or stopped mid-row
} epuck_camera_step;

// Bytes the camera sends per pixel (RGB565).
#define EPUCK_CAMERA_PIXEL_BYTES 2u

// Starts reading row `row` (0 = the first row of the configured window) of
// a coming frame: of every second pixel from the first (pixels 0, 2, 4...),
// `pixels` of them, the EPUCK_CAMERA_PIXEL_BYTES bytes go one after the
// other into `bytes`, which must stay valid until the read is done (a row
// cut short leaves there the bytes read so far). Replaces a read in
// progress.
void epuck_board_camera_start(hal_board *board, uint16_t row, uint8_t *bytes, uint16_t pixels);

// Advances the read, waiting at most a few hundred microseconds; says where
// it stands.
epuck_camera_step epuck_board_camera_step(hal_board *board);

#endif
