// Flash for a board whose flash cannot be written (QEMU's: its flash is a
// ROM and its flash interface does nothing): STM32F4_RAM_FLASH_UNITS units
// of STM32F4_RAM_FLASH_UNIT bytes in RAM, at the flash addresses from
// STM32F4_RAM_FLASH_BASE, with the flash's rules (erased bits read 1, a
// program only clears bits). The RAM is left alone by the start-up code
// (.noinit), so what is stored survives a reset, as in flash; a marker tells
// a first power-on, which erases it all. Other addresses read the real flash
// and cannot be erased or programmed. The entry point owns the memory
// (stm32f4_ram_flash in stm32f4_board.h) and gives it to the board.

#include "stm32f4_chip.h"
#include "stm32f4_registers.h"

#define RAM_FLASH_END (STM32F4_RAM_FLASH_BASE + STM32F4_RAM_FLASH_WORDS * HAL_FLASH_WORD_SPAN)

static bool in_ram_flash(uint32_t address)
{
    return address >= STM32F4_RAM_FLASH_BASE && address < RAM_FLASH_END;
}

static uint32_t *word_at(hal_board *board, uint32_t address)
{
    stm32f4_ram_flash *memory = board->ram_flash;

    if (memory->marker != STM32F4_RAM_FLASH_MARKER) {
        uint32_t i;
        for (i = 0; i < STM32F4_RAM_FLASH_WORDS; i++)
            memory->words[i] = HAL_FLASH_ERASED;
        memory->marker = STM32F4_RAM_FLASH_MARKER;
    }
    return &memory->words[(address - STM32F4_RAM_FLASH_BASE) / HAL_FLASH_WORD_SPAN];
}

uint32_t hal_flash_read(hal_board *board, uint32_t address)
{
    if (address % HAL_FLASH_WORD_SPAN != 0)
        return 0;
    if (in_ram_flash(address))
        return *word_at(board, address);
    if (address < STM32F4_FLASH_BASE || address >= HAL_FLASH_END)
        return 0;
    return stm32f4_read(address);
}

uint32_t hal_flash_unit(hal_board *board, uint32_t address, uint32_t *unit_start)
{
    (void)board;
    if (!in_ram_flash(address))
        return 0;
    *unit_start = address - (address - STM32F4_RAM_FLASH_BASE) % STM32F4_RAM_FLASH_UNIT;
    return STM32F4_RAM_FLASH_UNIT;
}

bool hal_flash_erase(hal_board *board, uint32_t unit_start)
{
    uint32_t *word;
    uint32_t i;

    if (!in_ram_flash(unit_start) ||
        (unit_start - STM32F4_RAM_FLASH_BASE) % STM32F4_RAM_FLASH_UNIT != 0)
        return false;
    word = word_at(board, unit_start);
    for (i = 0; i < STM32F4_RAM_FLASH_UNIT / HAL_FLASH_WORD_SPAN; i++)
        word[i] = HAL_FLASH_ERASED;
    return true;
}

bool hal_flash_program(hal_board *board, uint32_t address, const uint32_t *words, uint16_t count)
{
    uint32_t unit_start;
    uint32_t span = hal_flash_unit(board, address, &unit_start);
    uint32_t *word;
    uint16_t i;

    if (span == 0 || address % HAL_FLASH_WORD_SPAN != 0 ||
        (uint32_t)count * HAL_FLASH_WORD_SPAN > unit_start + span - address)
        return false;
    word = word_at(board, address);
    for (i = 0; i < count; i++)
        word[i] &= words[i];
    return true;
}
