// The hardware abstraction layer: what the portable firmware (the node's
// link, the bytecode store, the bootloader core, the robot's main loop) may
// ask of any chip. Short on purpose: time, the link to the hosts, the flash,
// critical sections, reset and idle.
//
// Each chip's port (ports/<chip>/) implements every function, and the
// target's one configuration header (boards/<board>/<board>_config.h),
// which every build names with TARGET_CONFIG, describes the chip: the
// link's buffers and the flash's words and units. What a pin or an analog
// input means on a robot is the robot's board interface
// (robots/<robot>/<robot>_board.h), which the board implements on the chip
// (boards/<board>/), not the chip's. A board is an instance (struct
// hal_board, defined by the port): the host holds many, a chip build
// exactly one. docs/porting.md says how to write a port.

#ifndef HAL_H
#define HAL_H

#include <stdbool.h>
#include <stdint.h>

#ifndef TARGET_CONFIG
#error "TARGET_CONFIG must name the target's configuration header (docs/porting.md)"
#endif
#include TARGET_CONFIG

#if !defined(HAL_LINK_RECEIVE_CAPACITY) || !defined(HAL_LINK_TRANSMIT_CAPACITY)
#error                                                                                             \
  "the target's configuration must give HAL_LINK_RECEIVE_CAPACITY and HAL_LINK_TRANSMIT_CAPACITY"
#endif
#if !defined(HAL_FLASH_WORD_BITS) || !defined(HAL_FLASH_WORD_SPAN) ||                              \
  !defined(HAL_FLASH_PROGRAM_WORDS) || !defined(HAL_FLASH_ERASED) || !defined(HAL_FLASH_END)
#error "the target's configuration must describe its flash (HAL_FLASH_*)"
#endif

// Defined by each port.
typedef struct hal_board hal_board;

// --- time ----------------------------------------------------------------------

// Milliseconds since the board started; wraps after 49 days.
uint32_t hal_milliseconds(hal_board *board);

// Waits about `microseconds` without giving up the processor (short waits such
// as a reset pulse; the host does not wait at all).
void hal_delay_microseconds(hal_board *board, uint16_t microseconds);

// --- the link to the hosts (a UART: the e-puck's Bluetooth, QEMU's serial) ----

// Takes up to `capacity` received bytes without waiting; returns how many.
// The port keeps HAL_LINK_RECEIVE_CAPACITY bytes until they are taken.
uint16_t hal_link_receive(hal_board *board, uint8_t *bytes, uint16_t capacity);

// Queues up to `count` bytes for sending, in order, without waiting; returns
// how many it took (fewer when its HAL_LINK_TRANSMIT_CAPACITY-byte buffer
// is full). The port sends them in the background (the UART's interrupt).
uint16_t hal_link_send(hal_board *board, const uint8_t *bytes, uint16_t count);

// How many bytes hal_link_send would take now.
uint16_t hal_link_send_room(hal_board *board);

// --- flash ------------------------------------------------------------------------
// Words of HAL_FLASH_WORD_BITS bits (24 on the dsPIC, 32 on a Cortex-M), at
// addresses HAL_FLASH_WORD_SPAN apart below HAL_FLASH_END; an erased word
// reads HAL_FLASH_ERASED. The chip erases whole units (a dsPIC row, an STM32
// sector: hal_flash_unit says which) and programs runs of
// HAL_FLASH_PROGRAM_WORDS words, whose bits can only go from 1 to 0.

// The word at `address`; 0 for an address outside flash or between words.
uint32_t hal_flash_read(hal_board *board, uint32_t address);

// The erase unit holding `address`: stores its first address in
// `*unit_start` and returns its span in address units; 0 outside flash.
uint32_t hal_flash_unit(hal_board *board, uint32_t address, uint32_t *unit_start);

// Erases the unit that begins at `unit_start`; false for an address where
// no unit begins, or when the chip reports a failure.
bool hal_flash_erase(hal_board *board, uint32_t unit_start);

// Programs `count` words (a multiple of HAL_FLASH_PROGRAM_WORDS) from
// `address` (the start of a run), within one erase unit; false for a bad
// address or count, or a failure. Read the words back to check them.
bool hal_flash_program(hal_board *board, uint32_t address, const uint32_t *words, uint16_t count);

// --- interrupts, reset, idle ----------------------------------------------------

typedef uint16_t hal_critical_state;

// Holds off every interrupt handler until the matching leave; returns what
// hal_critical_leave restores (sections nest).
hal_critical_state hal_critical_enter(hal_board *board);

// Ends the critical section begun by the hal_critical_enter that returned
// `state`.
void hal_critical_leave(hal_board *board, hal_critical_state state);

// Restarts the board (on the e-puck this enters the bootloader first). A
// chip never returns; the host records the request and returns.
void hal_reset(hal_board *board);

// Sleeps until something may have happened (an interrupt on a chip; the host
// scheduler decides). Returns at once when nothing can wait.
void hal_idle(hal_board *board);

#endif
