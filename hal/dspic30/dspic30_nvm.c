// Data EEPROM and program flash through run-time self-programming (§1.2 to
// §1.4): table reads, and erases/writes started with NVMCON and the
// 0x55/0xAA key sequence. Erases name their target in NVMADRU:NVMADR
// explicitly ([FPS] Table 11-5); writes select it through the table-write
// latches.

#include "dspic30_board.h"
#include "dspic30_registers.h"

#define ADDRESS_PAGE_SHIFT     16u
#define ADDRESS_OFFSET_MASK    0xFFFFul
#define WORD_ADDRESS_STEP      2u // PC units per word or instruction
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

uint16_t hal_eeprom_read(hal_board *board, uint16_t index)
{
    (void)board;
    if (index >= DSPIC30_EEPROM_WORDS)
        return HAL_EEPROM_ERASED;
    dspic30_write(DSPIC30_TBLPAG, DSPIC30_EEPROM_PAGE);
    return dspic30_table_read_low(eeprom_offset(index));
}

bool hal_eeprom_erase_word(hal_board *board, uint16_t index)
{
    if (index >= DSPIC30_EEPROM_WORDS)
        return false;
    set_erase_target(DSPIC30_EEPROM_PAGE, eeprom_offset(index));
    return run_operation(board, DSPIC30_NVMCON_EEPROM_WORD_ERASE);
}

bool hal_eeprom_write_word(hal_board *board, uint16_t index, uint16_t value)
{
    if (index >= DSPIC30_EEPROM_WORDS)
        return false;
    dspic30_write(DSPIC30_TBLPAG, DSPIC30_EEPROM_PAGE);
    dspic30_table_write_low(eeprom_offset(index), value);
    return run_operation(board, DSPIC30_NVMCON_EEPROM_WORD_WRITE);
}

static bool valid_row(uint32_t row_address)
{
    return row_address < DSPIC30_FLASH_END && row_address % DSPIC30_FLASH_ROW_SPAN == 0;
}

uint32_t hal_flash_read(hal_board *board, uint32_t address)
{
    uint16_t offset = (uint16_t)(address & ADDRESS_OFFSET_MASK);
    uint32_t high;

    (void)board;
    if (address >= DSPIC30_FLASH_END || address % WORD_ADDRESS_STEP != 0)
        return 0;
    dspic30_write(DSPIC30_TBLPAG, (uint16_t)(address >> ADDRESS_PAGE_SHIFT));
    high = dspic30_table_read_high(offset) & INSTRUCTION_HIGH_MASK;
    return (high << INSTRUCTION_HIGH_SHIFT) | dspic30_table_read_low(offset);
}

bool hal_flash_erase_row(hal_board *board, uint32_t row_address)
{
    if (!valid_row(row_address))
        return false;
    set_erase_target((uint16_t)(row_address >> ADDRESS_PAGE_SHIFT),
                     (uint16_t)(row_address & ADDRESS_OFFSET_MASK));
    return run_operation(board, DSPIC30_NVMCON_FLASH_ROW_ERASE);
}

bool hal_flash_write_row(hal_board *board, uint32_t row_address, const uint32_t *instructions)
{
    uint16_t offset = (uint16_t)(row_address & ADDRESS_OFFSET_MASK);
    uint16_t i;

    if (!valid_row(row_address))
        return false;
    // Fill the row's 32 write latches, then program them at once.
    dspic30_write(DSPIC30_TBLPAG, (uint16_t)(row_address >> ADDRESS_PAGE_SHIFT));
    for (i = 0; i < DSPIC30_FLASH_ROW_INSTRUCTIONS; i++) {
        uint16_t at = (uint16_t)(offset + WORD_ADDRESS_STEP * i);
        dspic30_table_write_low(at, (uint16_t)(instructions[i] & ADDRESS_OFFSET_MASK));
        dspic30_table_write_high(
          at, (uint16_t)((instructions[i] >> INSTRUCTION_HIGH_SHIFT) & INSTRUCTION_HIGH_MASK));
    }
    return run_operation(board, DSPIC30_NVMCON_FLASH_ROW_WRITE);
}
