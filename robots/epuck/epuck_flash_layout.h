// The e-puck's program flash, its dsPIC30F6014A's (ports/dspic30/
// dspic30_flash_geometry.h: 24-bit instructions, rows of 32 of them), and
// how this project divides it between its images. Addresses are
// program-counter addresses: 2 per instruction, 0x40 per row.
//
//   0x000000  BOOT_VECTORS_BASE      reset GOTO, IVT, AIVT: the bootloader image's,
//                                    never written by the Aseba bootloader
//   0x000100  BOOT_APPLICATION_START the application: its GOTO table (reset slot,
//                                    then one slot per interrupt vector), its code,
//                                    its descriptor in the last row
//   0x016380  STORE_REGION_BASE      the bytecode store (store/bytecode_store.h)
//   0x016F00  BOOT_LOADER_BASE       the Aseba bootloader's code and constants
//   0x017F00  BOOT_TINY_BASE         the factory Tiny Bootloader (fact sheet §4.1)
//   0x018000  HAL_FLASH_END
//
// Every boundary is one named constant; the linker scripts
// (linker/epuck-app.gld, linker/epuck-bootloader.gld) repeat them and
// tests/bootloader/linker_scripts_test.cpp checks that they agree. The sizes
// are chosen from the top of flash down, so moving one boundary means
// changing one size. The configuration of each e-puck target (the dsPIC
// board's and the simulated e-puck's, whose chip has this flash) includes
// this file, and so do the host tools that build and flash e-puck images.

#ifndef EPUCK_FLASH_LAYOUT_H
#define EPUCK_FLASH_LAYOUT_H

#include <stdint.h>

// The chip's flash as hal.h sees it: words, rows, HAL_FLASH_END.
#include "ports/dspic30/dspic30_flash_geometry.h"

// --- the bootloaders --------------------------------------------------------------
// The factory Tiny Bootloader: the last 4 rows (fact sheet §4.1).
#define BOOT_TINY_ROWS 4u
#define BOOT_TINY_BASE (HAL_FLASH_END - BOOT_TINY_ROWS * DSPIC30_FLASH_ROW_SPAN)

// The Aseba bootloader image's code and constants (its reset GOTO and vector
// tables are in rows 0-3): 64 rows = 2048 instructions (bootloader/README.md
// explains the size).
#define BOOT_LOADER_ROWS 64u
#define BOOT_LOADER_END  BOOT_TINY_BASE
#define BOOT_LOADER_BASE (BOOT_LOADER_END - BOOT_LOADER_ROWS * DSPIC30_FLASH_ROW_SPAN)

// --- the bytecode store -------------------------------------------------------------
// Two bytecode slots of 22 rows and two settings slots of one row; a store
// block is one row here.
#define STORE_REGION_ROWS          46u
#define STORE_REGION_END           BOOT_LOADER_BASE
#define STORE_REGION_BASE          (STORE_REGION_END - STORE_REGION_ROWS * DSPIC30_FLASH_ROW_SPAN)
#define STORE_BYTECODE_SLOT_BLOCKS 22u
#define STORE_SETTINGS_SLOT_BLOCKS 1u
#define STORE_BYTECODE_SLOT_0      STORE_REGION_BASE
#define STORE_BYTECODE_SLOT_1                                                                      \
    (STORE_BYTECODE_SLOT_0 + STORE_BYTECODE_SLOT_BLOCKS * DSPIC30_FLASH_ROW_SPAN)
#define STORE_SETTINGS_SLOT_0                                                                      \
    (STORE_BYTECODE_SLOT_1 + STORE_BYTECODE_SLOT_BLOCKS * DSPIC30_FLASH_ROW_SPAN)
#define STORE_SETTINGS_SLOT_1                                                                      \
    (STORE_SETTINGS_SLOT_0 + STORE_SETTINGS_SLOT_BLOCKS * DSPIC30_FLASH_ROW_SPAN)
#define STORE_ROWS_USED (2u * (STORE_BYTECODE_SLOT_BLOCKS + STORE_SETTINGS_SLOT_BLOCKS))
typedef char dspic30_store_fits_its_region[STORE_ROWS_USED <= STORE_REGION_ROWS ? 1 : -1];

// --- vectors and the application ---------------------------------------------------
// Rows 0-3 belong to the bootloader image: the reset GOTO at 0, the IVT at
// 0x04 + 2k, the AIVT at 0x84 + 2k (fact sheet §1.1, §1.7).
#define BOOT_VECTORS_BASE      0x000000ul
#define BOOT_VECTORS_ROWS      4u
#define BOOT_INTERRUPT_COUNT   62u // IVT entries
#define BOOT_IVT_BASE          0x000004ul
#define BOOT_AIVT_BASE         0x000084ul
#define BOOT_VECTOR_ENTRY_PC   2u // PC units per IVT entry (one instruction word)
#define BOOT_APPLICATION_START (BOOT_VECTORS_BASE + BOOT_VECTORS_ROWS * DSPIC30_FLASH_ROW_SPAN)
#define BOOT_APPLICATION_END   STORE_REGION_BASE // first PC address the bootloader never writes

// The application's GOTO table, at its first address: slot 0 is a GOTO to
// the application's start-up code (its "reset" slot, the entry the
// bootloader jumps to), slot 1 + k a GOTO to the handler of interrupt
// vector k, which the bootloader image's IVT entry k points at. Each slot is
// a two-instruction GOTO (4 PC units); the table takes 4 rows, the last slot
// unused, and the application's code starts after it.
#define BOOT_TABLE_BASE       BOOT_APPLICATION_START
#define BOOT_TABLE_SLOT_SPAN  4u // PC units: a GOTO is two instructions
#define BOOT_TABLE_ROWS       4u
#define BOOT_TABLE_END        (BOOT_TABLE_BASE + BOOT_TABLE_ROWS * DSPIC30_FLASH_ROW_SPAN)
#define BOOT_TABLE_RESET_SLOT BOOT_TABLE_BASE
#define BOOT_TABLE_INTERRUPT_SLOT(vector)                                                          \
    (BOOT_TABLE_BASE + BOOT_TABLE_SLOT_SPAN * (1ul + (uint32_t)(vector)))

// The entry the bootloader jumps to unless an image says otherwise, and the
// limit of entries: a 16-bit computed jump must reach them (§5.2).
#define BOOT_APPLICATION_ENTRY BOOT_TABLE_RESET_SLOT
#define BOOT_ENTRY_LIMIT       0x10000ul

// The GOTO instruction: opcode in bits 23:16 of the first word, target bits
// 15:0 there and bits 22:16 in the second word.
#define BOOT_GOTO_OPCODE      0x04u
#define BOOT_GOTO_HIGH_MASK   0x7Fu
#define BOOT_INSTRUCTION_BITS 24u

#endif
