// The STM32F405/407: the state behind hal.h, the start-up of each part, and
// the interrupt handlers as plain functions of the board. stm32f4_application_main.c
// owns the single instance and forwards the vectors of stm32f4_startup.c to
// these handlers.

#ifndef STM32F4_CHIP_H
#define STM32F4_CHIP_H

#include <stdbool.h>
#include <stdint.h>

#include "hal/hal.h"
#include "hal/hal_link_rings.h"

#ifdef STM32F4_RAM_FLASH_BASE
// The flash of a board that cannot write its own (stm32f4_ram_flash.c), in
// RAM the start-up code leaves alone (.noinit), so that it survives resets.
#define STM32F4_RAM_FLASH_WORDS                                                                    \
    (STM32F4_RAM_FLASH_UNITS * STM32F4_RAM_FLASH_UNIT / HAL_FLASH_WORD_SPAN)
typedef struct stm32f4_ram_flash {
    uint32_t marker; // STM32F4_RAM_FLASH_MARKER once erased at the first power-on
    uint32_t words[STM32F4_RAM_FLASH_WORDS];
} stm32f4_ram_flash;
#define STM32F4_RAM_FLASH_MARKER 0xF1A5C0DEul
#endif

struct hal_board {
    // Milliseconds since start-up, counted by SysTick's interrupt.
    volatile uint32_t milliseconds;

    // USART1's rings: received bytes from its interrupt, bytes to send to
    // its transmit-empty interrupt or by polling (STM32F4_TRANSMIT_BY_INTERRUPT).
    hal_link_rings link;

#ifdef STM32F4_RAM_FLASH_BASE
    stm32f4_ram_flash *ram_flash; // set by the entry point before stm32f4_board_init
#endif
};

// Starts the clock (the PLL when the board has a crystal), SysTick at
// 1 kHz and USART1; interrupts run from then on.
void stm32f4_board_init(hal_board *board);

// Each start-up step, in the order stm32f4_board_init calls them.
void stm32f4_clock_init(hal_board *board);
void stm32f4_usart_init(hal_board *board);

// Sends what the transmit ring holds while the USART takes it; the polling
// half of the link (the main loop calls it through hal_idle and
// hal_link_send).
void stm32f4_usart_drain(hal_board *board);

// The interrupt handlers.
void stm32f4_on_systick(hal_board *board);
void stm32f4_on_usart1(hal_board *board);

#endif
