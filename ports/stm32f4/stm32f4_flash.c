// The STM32F4's flash through its interface (RM0090 §3.6): reads straight
// from memory, sector erases and 32-bit programming after the unlock keys.
// The CPU stalls on flash reads while an erase runs (up to half a second for
// a 16 KiB sector, §3.6.3 and the data sheet), interrupts included: a board
// keeps its bytecode store in the small sectors. QEMU's board uses
// stm32f4_ram_flash.c instead (its flash interface does nothing).

#include "stm32f4_chip.h"
#include "stm32f4_registers.h"

// Polls of BSY before an operation is taken as failed: more than the
// slowest sector erase at 168 MHz.
#define BUSY_ATTEMPTS 100000000ul

// The sector holding `address`, its first address and its span; false
// outside flash.
static bool find_sector(uint32_t address, uint32_t *sector, uint32_t *start, uint32_t *span)
{
    if (address < STM32F4_FLASH_BASE || address >= HAL_FLASH_END)
        return false;
    if (address < STM32F4_FLASH_BASE + STM32F4_FLASH_SMALL_SECTORS * STM32F4_FLASH_SMALL_SECTOR) {
        *sector = (address - STM32F4_FLASH_BASE) / STM32F4_FLASH_SMALL_SECTOR;
        *span = STM32F4_FLASH_SMALL_SECTOR;
        *start = STM32F4_FLASH_BASE + *sector * STM32F4_FLASH_SMALL_SECTOR;
    } else if (address < STM32F4_FLASH_LARGE_BASE) {
        *sector = STM32F4_FLASH_SMALL_SECTORS;
        *span = STM32F4_FLASH_MEDIUM_SECTOR;
        *start = STM32F4_FLASH_LARGE_BASE - STM32F4_FLASH_MEDIUM_SECTOR;
    } else {
        uint32_t index = (address - STM32F4_FLASH_LARGE_BASE) / STM32F4_FLASH_LARGE_SECTOR;
        *sector = STM32F4_FLASH_SMALL_SECTORS + 1u + index;
        *span = STM32F4_FLASH_LARGE_SECTOR;
        *start = STM32F4_FLASH_LARGE_BASE + index * STM32F4_FLASH_LARGE_SECTOR;
    }
    return true;
}

// Waits for the interface to finish; true when it reports no error.
static bool wait_done(void)
{
    uint32_t attempts;
    uint32_t status;

    for (attempts = 0; attempts < BUSY_ATTEMPTS; attempts++) {
        status = stm32f4_read(STM32F4_FLASH_SR);
        if ((status & STM32F4_FLASH_SR_BSY) == 0) {
            stm32f4_write(STM32F4_FLASH_SR,
                          status & (STM32F4_FLASH_SR_ERRORS | STM32F4_FLASH_SR_EOP));
            return (status & STM32F4_FLASH_SR_ERRORS) == 0;
        }
    }
    return false;
}

static void unlock(void)
{
    if (stm32f4_read(STM32F4_FLASH_CR) & STM32F4_FLASH_CR_LOCK) {
        stm32f4_write(STM32F4_FLASH_KEYR, STM32F4_FLASH_KEY1);
        stm32f4_write(STM32F4_FLASH_KEYR, STM32F4_FLASH_KEY2);
    }
}

static void lock(void)
{
    stm32f4_write(STM32F4_FLASH_CR, STM32F4_FLASH_CR_LOCK);
}

uint32_t hal_flash_read(hal_board *board, uint32_t address)
{
    (void)board;
    if (address < STM32F4_FLASH_BASE || address >= HAL_FLASH_END ||
        address % HAL_FLASH_WORD_SPAN != 0)
        return 0;
    return stm32f4_read(address);
}

uint32_t hal_flash_unit(hal_board *board, uint32_t address, uint32_t *unit_start)
{
    uint32_t sector;
    uint32_t span;

    (void)board;
    return find_sector(address, &sector, unit_start, &span) ? span : 0;
}

bool hal_flash_erase(hal_board *board, uint32_t unit_start)
{
    uint32_t sector;
    uint32_t start;
    uint32_t span;
    bool ok;

    (void)board;
    if (!find_sector(unit_start, &sector, &start, &span) || start != unit_start)
        return false;
    unlock();
    ok = wait_done();
    if (ok) {
        stm32f4_write(STM32F4_FLASH_CR,
                      STM32F4_FLASH_CR_SER | STM32F4_FLASH_CR_PSIZE_32 |
                        sector << STM32F4_FLASH_CR_SNB_SHIFT);
        stm32f4_set_bits(STM32F4_FLASH_CR, STM32F4_FLASH_CR_STRT);
        ok = wait_done();
    }
    lock();
    return ok;
}

bool hal_flash_program(hal_board *board, uint32_t address, const uint32_t *words, uint16_t count)
{
    uint32_t sector;
    uint32_t start;
    uint32_t span;
    uint16_t i;
    bool ok;

    (void)board;
    if (!find_sector(address, &sector, &start, &span) || address % HAL_FLASH_WORD_SPAN != 0 ||
        (uint32_t)count * HAL_FLASH_WORD_SPAN > start + span - address)
        return false;
    unlock();
    ok = wait_done();
    stm32f4_write(STM32F4_FLASH_CR, STM32F4_FLASH_CR_PG | STM32F4_FLASH_CR_PSIZE_32);
    for (i = 0; i < count && ok; i++) {
        stm32f4_write(address + (uint32_t)i * HAL_FLASH_WORD_SPAN, words[i]);
        ok = wait_done();
    }
    lock();
    return ok;
}
