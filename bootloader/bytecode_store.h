// Fail-safe storage of records (the user's bytecode, the node's settings) in
// the program-flash rows of the linker's `bytecode_store` region.
//
// Every kind of record has two slots. A save always writes the slot that does
// not hold the newest valid record, so the newest valid record is never
// touched: a power cut at any moment of a save leaves either the old or the
// new record loadable. A slot holds a byte stream, 3 bytes per 24-bit
// instruction (low, middle, upper byte), that starts with a header of four
// little-endian 16-bit words:
//
//   magic     the kind of record (STORE_MAGIC_BYTECODE, STORE_MAGIC_SETTINGS)
//   sequence  one more than the slot it replaced (modulo 2^16)
//   count     how many 16-bit payload words follow
//   crc       CRC-16/XMODEM (node_crc16, seed 0) of magic, sequence, count
//             (2 bytes each, low byte first) then of the payload bytes
//
// then the payload words, low byte first. The row holding the header is
// erased first and written last, so a slot whose header is readable is
// complete unless a cut tore its first row, which the CRC then rejects.

#ifndef BYTECODE_STORE_H
#define BYTECODE_STORE_H

#include <stdbool.h>
#include <stdint.h>

#include "bootloader/flash_layout.h"
#include "hal/hal.h"

// The region (STORE_REGION_BASE, STORE_REGION_ROWS) is in flash_layout.h.

#define STORE_SLOT_COUNT            2u
#define STORE_BYTES_PER_INSTRUCTION 3u // the 24 bits of an instruction
#define STORE_ROW_BYTES             (HAL_FLASH_ROW_INSTRUCTIONS * STORE_BYTES_PER_INSTRUCTION)
#define STORE_HEADER_BYTES          8u // magic, sequence, count, crc
#define STORE_WORD_BYTES            2u

// How many rows a slot needs for `words` payload words.
#define STORE_ROWS_FOR_WORDS(words)                                                                \
    (((words)*STORE_WORD_BYTES + STORE_HEADER_BYTES + STORE_ROW_BYTES - 1u) / STORE_ROW_BYTES)

#define STORE_MAGIC_BYTECODE 0xB17Eu
#define STORE_MAGIC_SETTINGS 0x5E77u

// The e-puck layout: two bytecode slots, then two settings slots, from the
// start of the region; the remaining rows are unused.
#define EPUCK_STORE_BYTECODE_MAX_WORDS 1024u // the VM's bytecode array
#define EPUCK_STORE_BYTECODE_SLOT_ROWS STORE_ROWS_FOR_WORDS(EPUCK_STORE_BYTECODE_MAX_WORDS) // 22
#define EPUCK_STORE_SETTINGS_MAX_WORDS                                                             \
    ((STORE_ROW_BYTES - STORE_HEADER_BYTES) / STORE_WORD_BYTES) // 44: one row
#define EPUCK_STORE_SETTINGS_SLOT_ROWS 1u
#define EPUCK_STORE_BYTECODE_SLOT_0    STORE_REGION_BASE
#define EPUCK_STORE_BYTECODE_SLOT_1                                                                \
    (EPUCK_STORE_BYTECODE_SLOT_0 + EPUCK_STORE_BYTECODE_SLOT_ROWS * HAL_FLASH_ROW_SPAN)
#define EPUCK_STORE_SETTINGS_SLOT_0                                                                \
    (EPUCK_STORE_BYTECODE_SLOT_1 + EPUCK_STORE_BYTECODE_SLOT_ROWS * HAL_FLASH_ROW_SPAN)
#define EPUCK_STORE_SETTINGS_SLOT_1                                                                \
    (EPUCK_STORE_SETTINGS_SLOT_0 + EPUCK_STORE_SETTINGS_SLOT_ROWS * HAL_FLASH_ROW_SPAN)
#define EPUCK_STORE_ROWS_USED                                                                      \
    (STORE_SLOT_COUNT * (EPUCK_STORE_BYTECODE_SLOT_ROWS + EPUCK_STORE_SETTINGS_SLOT_ROWS))
typedef char epuck_store_fits_its_region[EPUCK_STORE_ROWS_USED <= STORE_REGION_ROWS ? 1 : -1];

// The settings record: word EPUCK_SETTINGS_NODE_ID is the node id the robot
// answers to (a valid id is 1..EPUCK_SETTINGS_NODE_ID_MAX); the words after
// it are for calibration.
#define EPUCK_SETTINGS_NODE_ID     0u
#define EPUCK_SETTINGS_NODE_ID_MAX 0xFFFEu // 0xFFFF is the broadcast address

// Where one kind of record lives.
typedef struct store_place {
    uint32_t slot_address[STORE_SLOT_COUNT]; // first row of each slot (PC address)
    uint16_t slot_rows;                      // rows per slot
    uint16_t magic;                          // the kind of record kept there
} store_place;

// What a valid slot holds, as read from its header.
typedef struct store_slot_header {
    uint16_t sequence;
    uint16_t count;
} store_slot_header;

// The most payload words a slot of `place` can hold.
uint16_t store_capacity(const store_place *place);

// Whether slot `slot` of `place` holds a complete record (magic, size, CRC);
// fills `header` when it does.
bool store_slot_valid(hal_board *board,
                      const store_place *place,
                      uint16_t slot,
                      store_slot_header *header);

// Writes `count` words as the new newest record of `place`, leaving the
// newest valid record untouched; returns true once the record is written and
// read back intact, false (the old record still loadable) when it does not
// fit or a flash operation fails.
bool store_save(hal_board *board, const store_place *place, const uint16_t *words, uint16_t count);

// Copies the newest valid record of `place` (sequence numbers compared
// modulo 2^16) into `words` and its length into `*count`; returns false,
// leaving `words` untouched, when no slot is valid or the record is longer
// than `capacity`.
bool store_load(hal_board *board,
                const store_place *place,
                uint16_t *words,
                uint16_t capacity,
                uint16_t *count);

// The e-puck's two places in the bytecode_store region.
void epuck_store_bytecode_place(store_place *place);
void epuck_store_settings_place(store_place *place);

// Saves the user's bytecode (up to EPUCK_STORE_BYTECODE_MAX_WORDS words);
// returns whether it is stored (store_save).
bool epuck_store_save_bytecode(hal_board *board, const uint16_t *bytecode, uint16_t count);

// Loads the newest stored bytecode; returns false when there is none. The
// caller then resets the VM (vm_reset: verified, `when` flags cleared) and runs init.
bool epuck_store_load_bytecode(hal_board *board,
                               uint16_t *bytecode,
                               uint16_t capacity,
                               uint16_t *count);

// Saves the settings words (node id, calibration; up to
// EPUCK_STORE_SETTINGS_MAX_WORDS); returns whether they are stored.
bool epuck_store_save_settings(hal_board *board, const uint16_t *settings, uint16_t count);

// Loads the newest stored settings; returns false when there are none.
bool epuck_store_load_settings(hal_board *board,
                               uint16_t *settings,
                               uint16_t capacity,
                               uint16_t *count);

// The node id of the robot, the same for the bootloader and the
// application: the one in the stored settings when they hold a valid one,
// else (selector_position & EPUCK_SELECTOR_NODE_MASK) + 1 (hardware §6.6).
uint16_t epuck_store_node_id(hal_board *board, uint16_t selector_position);

#endif
