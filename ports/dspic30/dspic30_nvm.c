// Program flash (hal.h: 24-bit words, erased and programmed a row at a time)
// and data EEPROM through run-time self-programming (§1.2 to §1.4): table
// reads, and erases/writes started with NVMCON and the 0x55/0xAA key
// sequence. Erases name their target in NVMADRU:NVMADR explicitly ([FPS]
// Table 11-5); writes select it through the table-write latches.

#include "dspic30_chip.h"
#include "dspic30_registers.h"

#define ADDRESS_PAGE_SHIFT     16u
#define ADDRESS_OFFSET_MASK    0xFFFFul
#define WORD_ADDRESS_STEP      2u // PC units per EEPROM word or instruction
#define INSTRUCTION_HIGH_SHIFT 16u
#define INSTRUCTION_HIGH_MASK  0x00FFu

// Starts the operation `code` in NVMCON and waits for it to end; false when
// it reports an error or never ends.
static bool run_operation(hal_board *board, uint16_t code)
{
    uint16_t attempts;
    hal_critical_state state;

    dspic30_write(DSPIC30_NVMCON, code);
    // The key sequence must not be interrupted (DISI inside, and we mask too
    // so that no handler reads flash while it is busy).
    state = hal_critical_enter(board);
    dspic30_nvm_unlock_and_start();
    hal_critical_leave(board, state);
    for (attempts = 0; attempts < DSPIC30_NVM_WAIT_ATTEMPTS; attempts++) {
        uint16_t control = dspic30_read(DSPIC30_NVMCON);
        if ((control & DSPIC30_NVMCON_WR) == 0)
            return (control & DSPIC30_NVMCON_WRERR) == 0;
    }
    return false;
}

static void set_erase_target(uint16_t page, uint16_t offset)
{
    dspic30_write(DSPIC30_NVMADRU, page);
    dspic30_write(DSPIC30_NVMADR, offset);
}

static uint16_t eeprom_offset(uint16_t index)
{
    return (uint16_t)(DSPIC30_EEPROM_BASE + WORD_ADDRESS_STEP * index);
}

uint16_t dspic30_eeprom_read(hal_board *board, uint16_t index)
{
    (void)board;
    if (index >= DSPIC30_EEPROM_WORDS)
        return DSPIC30_EEPROM_ERASED;
    dspic30_write(DSPIC30_TBLPAG, DSPIC30_EEPROM_PAGE);
    return dspic30_table_read_low(eeprom_offset(index));
}

bool dspic30_eeprom_erase_word(hal_board *board, uint16_t index)
{
    if (index >= DSPIC30_EEPROM_WORDS)
        return false;
    set_erase_target(DSPIC30_EEPROM_PAGE, eeprom_offset(index));
    return run_operation(board, DSPIC30_NVMCON_EEPROM_WORD_ERASE);
}

bool dspic30_eeprom_write_word(hal_board *board, uint16_t index, uint16_t value)
{
    if (index >= DSPIC30_EEPROM_WORDS)
        return false;
    dspic30_write(DSPIC30_TBLPAG, DSPIC30_EEPROM_PAGE);
    dspic30_table_write_low(eeprom_offset(index), value);
    return run_operation(board, DSPIC30_NVMCON_EEPROM_WORD_WRITE);
}

static bool valid_row(uint32_t row_address)
{
    return row_address < HAL_FLASH_END && row_address % DSPIC30_FLASH_ROW_SPAN == 0;
}

uint32_t hal_flash_read(hal_board *board, uint32_t address)
{
    uint16_t offset = (uint16_t)(address & ADDRESS_OFFSET_MASK);
    uint32_t high;

    (void)board;
    if (address >= HAL_FLASH_END || address % WORD_ADDRESS_STEP != 0)
        return 0;
    dspic30_write(DSPIC30_TBLPAG, (uint16_t)(address >> ADDRESS_PAGE_SHIFT));
    high = dspic30_table_read_high(offset) & INSTRUCTION_HIGH_MASK;
    return (high << INSTRUCTION_HIGH_SHIFT) | dspic30_table_read_low(offset);
}

uint32_t hal_flash_unit(hal_board *board, uint32_t address, uint32_t *unit_start)
{
    (void)board;
    if (address >= HAL_FLASH_END)
        return 0;
    *unit_start = address - address % DSPIC30_FLASH_ROW_SPAN;
    return DSPIC30_FLASH_ROW_SPAN;
}

bool hal_flash_erase(hal_board *board, uint32_t unit_start)
{
    if (!valid_row(unit_start))
        return false;
    set_erase_target((uint16_t)(unit_start >> ADDRESS_PAGE_SHIFT),
                     (uint16_t)(unit_start & ADDRESS_OFFSET_MASK));
    return run_operation(board, DSPIC30_NVMCON_FLASH_ROW_ERASE);
}

// Fills the row's 32 write latches, then programs them at once.
static bool program_row(hal_board *board, uint32_t row_address, const uint32_t *instructions)
{
    uint16_t offset = (uint16_t)(row_address & ADDRESS_OFFSET_MASK);
    uint16_t i;

    dspic30_write(DSPIC30_TBLPAG, (uint16_t)(row_address >> ADDRESS_PAGE_SHIFT));
    for (i = 0; i < DSPIC30_FLASH_ROW_INSTRUCTIONS; i++) {
        uint16_t at = (uint16_t)(offset + WORD_ADDRESS_STEP * i);
        dspic30_table_write_low(at, (uint16_t)(instructions[i] & ADDRESS_OFFSET_MASK));
        dspic30_table_write_high(
          at, (uint16_t)((instructions[i] >> INSTRUCTION_HIGH_SHIFT) & INSTRUCTION_HIGH_MASK));
    }
    return run_operation(board, DSPIC30_NVMCON_FLASH_ROW_WRITE);
}

bool hal_flash_program(hal_board *board, uint32_t address, const uint32_t *words, uint16_t count)
{
    uint16_t done;

    if (!valid_row(address) || count % DSPIC30_FLASH_ROW_INSTRUCTIONS != 0 ||
        (uint32_t)count * WORD_ADDRESS_STEP > HAL_FLASH_END - address)
        return false;
    for (done = 0; done < count; done = (uint16_t)(done + DSPIC30_FLASH_ROW_INSTRUCTIONS)) {
        if (!program_row(board, address + (uint32_t)done * WORD_ADDRESS_STEP, words + done))
            return false;
    }
    return true;
}
