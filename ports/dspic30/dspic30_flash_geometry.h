// The dsPIC30F6014A's program flash as hal.h sees it (hardware §1.1-§1.3):
// 24-bit instructions at program-counter addresses 2 apart, below
// 0x018000; a row of 32 instructions (0x40 PC units) is the unit the chip
// erases and programs. Every target with this chip includes it from its
// configuration, through the e-puck's flash map
// (robots/epuck/epuck_flash_layout.h), and so does the host, whose
// simulated e-puck has the same flash.

#ifndef DSPIC30_FLASH_GEOMETRY_H
#define DSPIC30_FLASH_GEOMETRY_H

#define HAL_FLASH_WORD_BITS     24u // one instruction
#define HAL_FLASH_WORD_SPAN     2u  // PC units per instruction
#define HAL_FLASH_PROGRAM_WORDS 32u // the chip programs a whole row at once
#define HAL_FLASH_ERASED        0xFFFFFFul
#define HAL_FLASH_END           0x018000ul

// The erase unit: one row.
#define DSPIC30_FLASH_ROW_INSTRUCTIONS 32u
#define DSPIC30_FLASH_ROW_SPAN         0x40ul

#endif
