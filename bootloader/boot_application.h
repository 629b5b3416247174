// The application as the bootloader sees it: the flash pages it may write,
// and the descriptor that says whether a complete application is there.
//
// The application region is BOOT_APPLICATION_START up to
// BOOT_APPLICATION_END, both from the target's flash layout (on the e-puck,
// robots/epuck/epuck_flash_layout.h: 0x100 up to the bytecode store). It
// starts with the application's entry (on the e-puck, a GOTO table, which
// the bootloader image's vectors lead to); its last page holds the
// descriptor, which the host tool (tools/flash) adds to the image; its
// words are:
//
//   0  BOOT_DESCRIPTOR_MAGIC
//   1  entry: the PC address the bootloader jumps to, normally
//      BOOT_APPLICATION_ENTRY (the table's reset slot); below
//      BOOT_ENTRY_LIMIT so that a 16-bit computed jump reaches it
//   2  end: first PC address after the application's code (even,
//      BOOT_APPLICATION_START < end <= BOOT_DESCRIPTOR_ADDRESS)
//   3  CRC-16/XMODEM (node_crc16, seed 0) of every word from
//      BOOT_APPLICATION_START to end, HAL_FLASH_WORD_BITS / 8 bytes each,
//      low byte first
//
// What lies below the region (on the e-puck, rows 0-3: reset GOTO, IVT,
// AIVT) is the bootloader image's: no page of the application covers it, so
// no flashing ever erases the reset vector.

#ifndef BOOT_APPLICATION_H
#define BOOT_APPLICATION_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/hal.h"

// A page: BOOT_PAGE_WORDS flash words; the unit the bootloader writes, and
// on the e-puck one row.
#define BOOT_PAGE_WORDS 32u
#define BOOT_PAGE_SPAN  (BOOT_PAGE_WORDS * HAL_FLASH_WORD_SPAN) // address units

#define BOOT_DESCRIPTOR_ADDRESS (BOOT_APPLICATION_END - BOOT_PAGE_SPAN)
#define BOOT_CHECKED_START      BOOT_APPLICATION_START // the CRC covers the whole application
#define BOOT_DESCRIPTOR_MAGIC   0xA5EB01ul
#define BOOT_DESCRIPTOR_WORDS   4u // magic, entry, end, crc

// Instruction indexes in the descriptor row.
#define BOOT_DESCRIPTOR_MAGIC_INDEX 0u
#define BOOT_DESCRIPTOR_ENTRY_INDEX 1u
#define BOOT_DESCRIPTOR_END_INDEX   2u
#define BOOT_DESCRIPTOR_CRC_INDEX   3u

// CRC-16/XMODEM of the words of [start, end), HAL_FLASH_WORD_BITS / 8 bytes
// each, low first.
uint16_t boot_flash_crc(hal_board *board, uint32_t start, uint32_t end);

// Whether the descriptor is present and the application's CRC matches;
// gives the entry address when it does.
bool boot_application_valid(hal_board *board, uint32_t *entry);

#endif
