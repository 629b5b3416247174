// The simulated e-puck on a PC, its chip simulated along: hal.h and the
// e-puck's board interface (robots/epuck/epuck_board.h) over plain memory.
//
// The host program owns the board and drives it: it moves the board's clock
// forward (which fires the timers and ADC scans that fall due, in time
// order), puts received bytes in, and takes the bytes the firmware sends
// through a callback. What the pins see comes from a world (host_world.h).
// Data EEPROM and program flash keep the chip's erase-before-write rules,
// can be saved to and loaded from a file, and can lose power at a chosen
// operation. Nothing here touches the operating system except the two file
// functions, so tests and the simulator can wire boards together as they
// like. The sizes are the host target's (epuck_host_config.h).

#ifndef HOST_BOARD_H
#define HOST_BOARD_H

#include <stdbool.h>
#include <stdint.h>

#include "robots/epuck/epuck_board.h"
#include "hal/hal.h"
#include "host_world.h"

// Program-flash words modelled: every instruction below HAL_FLASH_END.
#define HOST_FLASH_WORDS   (HAL_FLASH_END / HAL_FLASH_WORD_SPAN)
#define HOST_EEPROM_ERASED 0xFFFFu

// No fault injection planned.
#define HOST_NO_POWER_CUT (-1L)

// Cycles from one ADC scan to the next.
#define HOST_ADC_SCAN_PERIOD_CYCLES (HOST_CYCLES_PER_SECOND / EPUCK_ADC_SCAN_RATE_HZ)

typedef struct host_periodic {
    epuck_callback callback;
    void *context;
    uint64_t period;   // cycles
    uint64_t next_due; // cycle of the next call
    bool running;
} host_periodic;

struct hal_board {
    uint64_t cycles; // simulated time since start

    uint8_t receive[HAL_LINK_RECEIVE_CAPACITY];
    uint16_t receive_start;
    uint16_t receive_count;
    // Where the firmware's bytes go; called from hal_link_send.
    void (*link_output)(void *context, const uint8_t *bytes, uint16_t count);
    void *link_context;

    host_periodic timers[EPUCK_TIMER_COUNT];
    // The ADC scan: a periodic event whose callback gets the values.
    epuck_adc_scan_callback adc_scan_callback;
    epuck_adc_scan_run_callback adc_scan_run_callback; // NULL: one scan at a time
    void *adc_scan_context;
    uint16_t adc_scan_mask;
    uint8_t adc_scan_channels; // in the mask
    uint64_t adc_next_due;

    const host_world *world;
    bool outputs[EPUCK_PIN_COUNT];
    bool last_input[EPUCK_PIN_COUNT]; // for edge detection
    epuck_callback edge_callback[EPUCK_PIN_COUNT];
    void *edge_context[EPUCK_PIN_COUNT];
    // The camera read in progress (epuck_board_camera_start): it completes
    // at its first step.
    uint8_t *camera_bytes;
    uint16_t camera_row;
    uint16_t camera_pixels;

    uint16_t critical_depth;
    bool reset_requested;
    // Counts the starts and stops of timers and pin watches, so that the
    // scheduler knows when a callback changed what falls due next.
    uint32_t configuration_changes;
    // Whether the world is asked for input changes, as worked out at
    // configuration_changes == inputs_watched_at.
    uint32_t inputs_watched_at;
    bool inputs_watched;
    // The running timer due first (-1: none) and its cycle, as worked out
    // at configuration_changes == first_timer_at: the scheduler looks for
    // it again only when a timer fired or a peripheral started or stopped.
    uint32_t first_timer_at;
    int16_t first_timer;
    uint64_t first_timer_due;

    uint16_t eeprom[HOST_EEPROM_WORDS];
    uint32_t flash[HOST_FLASH_WORDS];
    // Erase/write operations done so far, and the one that loses power
    // (HOST_NO_POWER_CUT for none); after the cut every operation fails.
    uint32_t memory_operations;
    long power_cut_at;
    bool powered_off;
};

// Prepares a board at time 0 in the flat world, with an empty link whose
// output goes to `link_output` (which may be NULL to drop it), EEPROM and
// flash erased, no timer running.
void host_board_init(hal_board *board,
                     void (*link_output)(void *context, const uint8_t *bytes, uint16_t count),
                     void *link_context);

// Makes `world` (which must outlive the board) supply what the pins see.
void host_board_set_world(hal_board *board, const host_world *world);

// Moves the clock to `milliseconds` since start, firing what falls due; time
// never goes backwards.
void host_board_set_time(hal_board *board, uint32_t milliseconds);

// Moves the clock forward by `cycles` processor cycles, calling every timer
// and ADC-scan callback that falls due at its time, and signalling the
// edges of watched input pins at the cycles the world says they may change,
// earliest first (at equal times: the ADC scan, the timers in epuck_timer
// order, then the inputs); but a run of scans the world holds steady goes
// to the firmware before the timers due during it (epuck_board.h).
void host_board_advance(hal_board *board, uint64_t cycles);

// Processor cycles since start (HOST_CYCLES_PER_SECOND a second).
uint64_t host_board_cycles(const hal_board *board);

// Bytes the link can still take.
uint16_t host_board_link_room(const hal_board *board);

// Puts received bytes on the link; returns false, taking nothing, when they
// do not all fit.
bool host_board_link_deliver(hal_board *board, const uint8_t *bytes, uint16_t count);

// The world says input `pin` may have changed: a watched falling edge calls
// its callback.
void host_board_input_changed(hal_board *board, epuck_pin pin);

// Whether the firmware asked for a reset since the last call (then clears it).
bool host_board_take_reset(hal_board *board);

// Resets the chip: timers, ADC scan, pin watches and outputs stop, received
// bytes are dropped; time, world, link wiring and memories stay.
void host_board_reset(hal_board *board);

// Makes the `count`-th erase or write from now (1 = the next) lose power:
// that operation takes effect on the first half of its words only (none for a
// single word) and fails, as does every later one until power comes back.
void host_board_cut_power_at(hal_board *board, uint32_t count);

// Restores power after a cut; memory keeps what the cut left.
void host_board_restore_power(hal_board *board);

// The simulated data EEPROM (HOST_EEPROM_WORDS words, NOR rules like the
// flash): the word at `index` (HOST_EEPROM_ERASED out of range), erasing one
// word, programming one erased word; false out of range or without power.
uint16_t host_board_eeprom_read(const hal_board *board, uint16_t index);
bool host_board_eeprom_erase_word(hal_board *board, uint16_t index);
bool host_board_eeprom_write_word(hal_board *board, uint16_t index, uint16_t value);

// Saves EEPROM and flash to `path`; returns false on an I/O error.
bool host_board_save_memory(const hal_board *board, const char *path);

// Loads EEPROM and flash saved by host_board_save_memory; returns false,
// changing nothing, when the file is missing or of the wrong size.
bool host_board_load_memory(hal_board *board, const char *path);

#endif
