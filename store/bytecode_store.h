// Fail-safe storage of records (the user's bytecode, the node's settings) in
// the flash region the target's configuration reserves for them
// (STORE_BYTECODE_SLOT_0 ... in boards/<board>/*_config.h), through hal.h.
//
// Every kind of record has two slots. A save always writes the slot that does
// not hold the newest valid record, so the newest valid record is never
// touched: a power cut at any moment of a save leaves either the old or the
// new record loadable. A slot holds a byte stream, HAL_FLASH_WORD_BITS / 8
// bytes per flash word (low byte first: 3 per dsPIC instruction, 4 per
// Cortex-M word), that starts with a header of four little-endian 16-bit
// words:
//
//   magic     the kind of record (STORE_MAGIC_BYTECODE, STORE_MAGIC_SETTINGS)
//   sequence  one more than the slot it replaced (modulo 2^16)
//   count     how many 16-bit payload words follow
//   crc       CRC-16/XMODEM (node_crc16, seed 0) of magic, sequence, count
//             (2 bytes each, low byte first) then of the payload bytes
//
// then the payload words, low byte first. A slot is written in blocks of
// STORE_BLOCK_WORDS flash words; the erase units under the record are erased
// first and the block holding the header is written last, so a slot whose
// header is readable is complete unless a cut tore its first block, which the
// CRC then rejects. A slot must begin where an erase unit begins, and own
// every unit it reaches.

#ifndef BYTECODE_STORE_H
#define BYTECODE_STORE_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/hal.h"

#if !defined(STORE_BYTECODE_SLOT_0) || !defined(STORE_BYTECODE_SLOT_1) ||                          \
  !defined(STORE_SETTINGS_SLOT_0) || !defined(STORE_SETTINGS_SLOT_1) ||                            \
  !defined(STORE_BYTECODE_SLOT_BLOCKS) || !defined(STORE_SETTINGS_SLOT_BLOCKS)
#error "the target's configuration must place the store's slots (STORE_*_SLOT_*, docs/porting.md)"
#endif

#define STORE_SLOT_COUNT     2u
#define STORE_BLOCK_WORDS    32u // flash words written at once
#define STORE_BYTES_PER_WORD (HAL_FLASH_WORD_BITS / 8u)
#define STORE_BLOCK_BYTES    (STORE_BLOCK_WORDS * STORE_BYTES_PER_WORD)
#define STORE_BLOCK_SPAN     (STORE_BLOCK_WORDS * HAL_FLASH_WORD_SPAN) // address units
#define STORE_HEADER_BYTES   8u // magic, sequence, count, crc
#define STORE_WORD_BYTES     2u
typedef char
  store_block_is_whole_program_runs[STORE_BLOCK_WORDS % HAL_FLASH_PROGRAM_WORDS == 0 ? 1 : -1];

// How many blocks a slot needs for `words` payload words, and the most
// payload words `blocks` blocks hold.
#define STORE_BLOCKS_FOR_WORDS(words)                                                              \
    (((words)*STORE_WORD_BYTES + STORE_HEADER_BYTES + STORE_BLOCK_BYTES - 1u) / STORE_BLOCK_BYTES)
#define STORE_CAPACITY_WORDS(blocks)                                                               \
    (((uint32_t)(blocks)*STORE_BLOCK_BYTES - STORE_HEADER_BYTES) / STORE_WORD_BYTES)

// What the target's slots hold: the firmware checks that the bytecode fits.
#define STORE_BYTECODE_CAPACITY_WORDS STORE_CAPACITY_WORDS(STORE_BYTECODE_SLOT_BLOCKS)
#define STORE_SETTINGS_CAPACITY_WORDS STORE_CAPACITY_WORDS(STORE_SETTINGS_SLOT_BLOCKS)

#define STORE_MAGIC_BYTECODE 0xB17Eu
#define STORE_MAGIC_SETTINGS 0x5E77u

// The settings record, at most STORE_SETTINGS_WORDS words (the target's
// configuration sets how many): word STORE_SETTINGS_NODE_ID is the node id
// the robot answers to (a valid id is 1..STORE_SETTINGS_NODE_ID_MAX); the
// words after it are for calibration.
#ifndef STORE_SETTINGS_WORDS
#error "the target's configuration must give STORE_SETTINGS_WORDS (docs/porting.md)"
#endif
#define STORE_SETTINGS_NODE_ID     0u
#define STORE_SETTINGS_NODE_ID_MAX 0xFFFEu // 0xFFFF is the broadcast address

// Where one kind of record lives.
typedef struct store_place {
    uint32_t slot_address[STORE_SLOT_COUNT]; // where each slot begins
    uint16_t slot_blocks;                    // blocks per slot
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

// The target's two places (its configuration's STORE_* slots).
void store_bytecode_place(store_place *place);
void store_settings_place(store_place *place);

// Saves the user's bytecode (up to STORE_BYTECODE_CAPACITY_WORDS words);
// returns whether it is stored (store_save).
bool store_save_bytecode(hal_board *board, const uint16_t *bytecode, uint16_t count);

// Loads the newest stored bytecode; returns false when there is none. The
// caller then resets the VM (vm_reset: verified, `when` flags cleared) and runs init.
bool store_load_bytecode(hal_board *board, uint16_t *bytecode, uint16_t capacity, uint16_t *count);

// Saves the settings words (node id, calibration; up to
// STORE_SETTINGS_CAPACITY_WORDS, of which the node reads
// STORE_SETTINGS_WORDS); returns whether they are stored.
bool store_save_settings(hal_board *board, const uint16_t *settings, uint16_t count);

// Loads the newest stored settings; returns false when there are none.
bool store_load_settings(hal_board *board, uint16_t *settings, uint16_t capacity, uint16_t *count);

// The node id of the robot, the same for the bootloader and the
// application: the one in the stored settings when they hold a valid one,
// else `without_settings` (the e-puck's comes from its selector:
// epuck_selector_node_id).
uint16_t store_node_id(hal_board *board, uint16_t without_settings);

#endif
