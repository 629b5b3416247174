// The STM32F405/407's flash as hal.h sees it (RM0090 §3.3): 1 MiB at
// 0x08000000 in twelve sectors (four of 16 KiB, one of 64 KiB, seven of
// 128 KiB), the unit an erase takes; programmed 32 bits at a time. Every
// board of the port includes it from its configuration header.

#ifndef STM32F4_FLASH_GEOMETRY_H
#define STM32F4_FLASH_GEOMETRY_H

#define HAL_FLASH_WORD_BITS     32u
#define HAL_FLASH_WORD_SPAN     4u // bytes
#define HAL_FLASH_PROGRAM_WORDS 1u
#define HAL_FLASH_ERASED        0xFFFFFFFFul
#define HAL_FLASH_END           0x08100000ul

#define STM32F4_FLASH_BASE          0x08000000ul
#define STM32F4_FLASH_SMALL_SECTORS 4u // sectors 0-3: 16 KiB
#define STM32F4_FLASH_SMALL_SECTOR  0x4000ul
#define STM32F4_FLASH_MEDIUM_SECTOR 0x10000ul // sector 4: 64 KiB
#define STM32F4_FLASH_LARGE_SECTOR  0x20000ul // sectors 5-11: 128 KiB
#define STM32F4_FLASH_LARGE_BASE    0x08020000ul

#endif
