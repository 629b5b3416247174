// The application as the bootloader sees it: the flash rows it may write,
// and the descriptor that says whether a complete application is there.
//
// The application region is BOOT_APPLICATION_START (0x100) up to the
// bytecode store (flash_layout.h). It starts with the application's GOTO
// table, which the bootloader image's vectors lead to; its last row holds
// the descriptor, which the host tool (tools/flash) adds to the image; its
// instructions are:
//
//   0  BOOT_DESCRIPTOR_MAGIC
//   1  entry: the PC address the bootloader jumps to, normally
//      BOOT_APPLICATION_ENTRY (the table's reset slot); below
//      BOOT_ENTRY_LIMIT so that a 16-bit computed jump reaches it
//   2  end: first PC address after the application's code (even,
//      BOOT_APPLICATION_START < end <= BOOT_DESCRIPTOR_ADDRESS)
//   3  CRC-16/XMODEM (node_crc16, seed 0) of every instruction from
//      BOOT_APPLICATION_START to end, 3 bytes each, low byte first
//
// Rows 0-3 (reset GOTO, IVT, AIVT) are the bootloader image's: no page of
// the application covers them, so no flashing ever erases the reset vector.

#ifndef BOOT_APPLICATION_H
#define BOOT_APPLICATION_H

#include <stdbool.h>
#include <stdint.h>

#include "bootloader/bytecode_store.h"
#include "bootloader/flash_layout.h"
#include "hal/hal.h"

#define BOOT_DESCRIPTOR_ADDRESS (BOOT_APPLICATION_END - HAL_FLASH_ROW_SPAN)
#define BOOT_CHECKED_START      BOOT_APPLICATION_START // the CRC covers the whole application
#define BOOT_APPLICATION_ENTRY  BOOT_TABLE_RESET_SLOT  // the entry unless the image says otherwise
#define BOOT_ENTRY_LIMIT        0x10000ul              // entries stay where a 16-bit jump reaches
#define BOOT_DESCRIPTOR_MAGIC   0xA5EB01ul
#define BOOT_DESCRIPTOR_WORDS   4u // magic, entry, end, crc

// Instruction indexes in the descriptor row.
#define BOOT_DESCRIPTOR_MAGIC_INDEX 0u
#define BOOT_DESCRIPTOR_ENTRY_INDEX 1u
#define BOOT_DESCRIPTOR_END_INDEX   2u
#define BOOT_DESCRIPTOR_CRC_INDEX   3u

// The GOTO instruction: opcode in bits 23:16 of the first word, target bits
// 15:0 there and bits 22:16 in the second word.
#define BOOT_GOTO_OPCODE      0x04u
#define BOOT_GOTO_HIGH_MASK   0x7Fu
#define BOOT_INSTRUCTION_BITS 24u

// CRC-16/XMODEM of the instructions of [start, end), 3 bytes each, low first.
uint16_t boot_flash_crc(hal_board *board, uint32_t start, uint32_t end);

// Whether the descriptor is present and the application's CRC matches;
// gives the entry address when it does.
bool boot_application_valid(hal_board *board, uint32_t *entry);

#endif
