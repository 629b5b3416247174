// The e-puck's program flash as this project divides it (PC addresses; a
// row is HAL_FLASH_ROW_SPAN = 0x40 PC units, 32 instructions). Every
// boundary is one named constant here; the linker scripts
// (linker/epuck-app.gld, linker/epuck-bootloader.gld) repeat them, and
// tests/bootloader/linker_scripts_test.cpp checks that they agree.
//
//   0x000000  BOOT_VECTORS_BASE      reset GOTO, IVT, AIVT: the bootloader image's,
//                                    never written by the Aseba bootloader
//   0x000100  BOOT_APPLICATION_START the application: its GOTO table (reset slot,
//                                    then one slot per interrupt vector), its code,
//                                    its descriptor in the last row
//   0x016380  STORE_REGION_BASE      the bytecode store (bytecode_store.h)
//   0x016F00  BOOT_LOADER_BASE       the Aseba bootloader's code and constants
//   0x017F00  BOOT_TINY_BASE         the factory Tiny Bootloader (fact sheet §4.1)
//   0x018000  HAL_FLASH_END
//
// The sizes are chosen from the top of flash down, so moving one boundary
// means changing one size.

#ifndef FLASH_LAYOUT_H
#define FLASH_LAYOUT_H

#include "hal/hal.h"

// The factory Tiny Bootloader: the last 4 rows (fact sheet §4.1).
#define BOOT_TINY_ROWS 4u
#define BOOT_TINY_BASE (HAL_FLASH_END - BOOT_TINY_ROWS * HAL_FLASH_ROW_SPAN)

// The Aseba bootloader image's code and constants (its reset GOTO and vector
// tables are in rows 0-3): 64 rows = 2048 instructions (bootloader/README.md
// explains the size).
#define BOOT_LOADER_ROWS 64u
#define BOOT_LOADER_END  BOOT_TINY_BASE
#define BOOT_LOADER_BASE (BOOT_LOADER_END - BOOT_LOADER_ROWS * HAL_FLASH_ROW_SPAN)

// The bytecode store: two bytecode slots of 22 rows and two settings slots
// of one row (bytecode_store.h checks that they fit).
#define STORE_REGION_ROWS 46u
#define STORE_REGION_END  BOOT_LOADER_BASE
#define STORE_REGION_BASE (STORE_REGION_END - STORE_REGION_ROWS * HAL_FLASH_ROW_SPAN)

// Rows 0-3 belong to the bootloader image: the reset GOTO at 0, the IVT at
// 0x04 + 2k, the AIVT at 0x84 + 2k (fact sheet §1.1, §1.7).
#define BOOT_VECTORS_BASE      0x000000ul
#define BOOT_VECTORS_ROWS      4u
#define BOOT_INTERRUPT_COUNT   62u // IVT entries
#define BOOT_IVT_BASE          0x000004ul
#define BOOT_AIVT_BASE         0x000084ul
#define BOOT_VECTOR_ENTRY_PC   2u // PC units per IVT entry (one instruction word)
#define BOOT_APPLICATION_START (BOOT_VECTORS_BASE + BOOT_VECTORS_ROWS * HAL_FLASH_ROW_SPAN)
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
#define BOOT_TABLE_END        (BOOT_TABLE_BASE + BOOT_TABLE_ROWS * HAL_FLASH_ROW_SPAN)
#define BOOT_TABLE_RESET_SLOT BOOT_TABLE_BASE
#define BOOT_TABLE_INTERRUPT_SLOT(vector)                                                          \
    (BOOT_TABLE_BASE + BOOT_TABLE_SLOT_SPAN * (1ul + (uint32_t)(vector)))

#endif
