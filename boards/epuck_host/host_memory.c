// The host board's data EEPROM and program flash: NOR semantics (an erase
// sets every bit, a write can only clear bits), the e-puck's sizes and rows
// (the flash geometry of epuck_host_config.h), power cuts at a chosen operation,
// and saving to a file.

#include "host_board.h"

#include <stdio.h>

#define INSTRUCTION_BYTES (HAL_FLASH_WORD_BITS / 8u) // in the memory file, little-endian
#define ROW_WORDS         DSPIC30_FLASH_ROW_INSTRUCTIONS
#define EEPROM_WORD_BYTES 2u
#define BITS_PER_BYTE     8u
#define BYTE_MASK         0xFFu

// Counts one erase/write; false when power is off or goes off now (`*cut`
// then says the operation is the interrupted one).
static bool start_operation(hal_board *board, bool *cut)
{
    *cut = false;
    if (board->powered_off)
        return false;
    board->memory_operations++;
    if (board->power_cut_at != HOST_NO_POWER_CUT &&
        (long)board->memory_operations == board->power_cut_at) {
        board->powered_off = true;
        *cut = true;
        return false;
    }
    return true;
}

void host_board_cut_power_at(hal_board *board, uint32_t count)
{
    board->power_cut_at = (long)(board->memory_operations + count);
}

void host_board_restore_power(hal_board *board)
{
    board->powered_off = false;
    board->power_cut_at = HOST_NO_POWER_CUT;
}

uint16_t host_board_eeprom_read(const hal_board *board, uint16_t index)
{
    if (index >= HOST_EEPROM_WORDS)
        return HOST_EEPROM_ERASED;
    return board->eeprom[index];
}

bool host_board_eeprom_erase_word(hal_board *board, uint16_t index)
{
    bool cut;
    if (index >= HOST_EEPROM_WORDS || !start_operation(board, &cut))
        return false;
    board->eeprom[index] = HOST_EEPROM_ERASED;
    return true;
}

bool host_board_eeprom_write_word(hal_board *board, uint16_t index, uint16_t value)
{
    bool cut;
    if (index >= HOST_EEPROM_WORDS || !start_operation(board, &cut))
        return false;
    board->eeprom[index] &= value;
    return true;
}

uint32_t hal_flash_read(hal_board *board, uint32_t address)
{
    if (address >= HAL_FLASH_END || address % HAL_FLASH_WORD_SPAN != 0)
        return 0;
    return board->flash[address / HAL_FLASH_WORD_SPAN];
}

uint32_t hal_flash_unit(hal_board *board, uint32_t address, uint32_t *unit_start)
{
    (void)board;
    if (address >= HAL_FLASH_END)
        return 0;
    *unit_start = address - address % DSPIC30_FLASH_ROW_SPAN;
    return DSPIC30_FLASH_ROW_SPAN;
}

// Starts a row operation and says how many words of the row it reaches: all
// of them, half when the power is cut during it, none when it fails before
// starting (*ok false in the last two cases).
static uint16_t row_reach(hal_board *board, bool *ok)
{
    bool cut;

    *ok = start_operation(board, &cut);
    if (cut)
        return ROW_WORDS / 2u;
    return *ok ? ROW_WORDS : 0;
}

bool hal_flash_erase(hal_board *board, uint32_t unit_start)
{
    uint32_t first = unit_start / HAL_FLASH_WORD_SPAN;
    bool ok;
    uint16_t count;
    uint16_t i;

    if (unit_start >= HAL_FLASH_END || unit_start % DSPIC30_FLASH_ROW_SPAN != 0)
        return false;
    count = row_reach(board, &ok);
    for (i = 0; i < count; i++)
        board->flash[first + i] = HAL_FLASH_ERASED;
    return ok;
}

bool hal_flash_program(hal_board *board, uint32_t address, const uint32_t *words, uint16_t count)
{
    uint16_t done;

    // As on the chip: whole rows, one operation each.
    if (address >= HAL_FLASH_END || address % DSPIC30_FLASH_ROW_SPAN != 0 ||
        count % HAL_FLASH_PROGRAM_WORDS != 0 ||
        (uint32_t)count * HAL_FLASH_WORD_SPAN > HAL_FLASH_END - address)
        return false;
    for (done = 0; done < count; done = (uint16_t)(done + ROW_WORDS)) {
        uint32_t first = address / HAL_FLASH_WORD_SPAN + done;
        bool ok;
        uint16_t reach = row_reach(board, &ok);
        uint16_t i;
        for (i = 0; i < reach; i++)
            board->flash[first + i] &= words[done + i] & HAL_FLASH_ERASED;
        if (!ok)
            return false;
    }
    return true;
}

// The file: every EEPROM word (2 bytes), then every flash instruction (3
// bytes), little-endian.
bool host_board_save_memory(const hal_board *board, const char *path)
{
    FILE *file = fopen(path, "wb");
    uint32_t i;
    uint16_t b;
    bool ok = file != NULL;

    for (i = 0; ok && i < HOST_EEPROM_WORDS; i++) {
        for (b = 0; b < EEPROM_WORD_BYTES; b++)
            ok = fputc((int)((board->eeprom[i] >> (BITS_PER_BYTE * b)) & BYTE_MASK), file) != EOF;
    }
    for (i = 0; ok && i < HOST_FLASH_WORDS; i++) {
        for (b = 0; ok && b < INSTRUCTION_BYTES; b++)
            ok = fputc((int)((board->flash[i] >> (BITS_PER_BYTE * b)) & BYTE_MASK), file) != EOF;
    }
    if (file != NULL && fclose(file) != 0)
        ok = false;
    return ok;
}

bool host_board_load_memory(hal_board *board, const char *path)
{
    static const long expected =
      (long)HOST_EEPROM_WORDS * EEPROM_WORD_BYTES + (long)HOST_FLASH_WORDS * INSTRUCTION_BYTES;
    FILE *file = fopen(path, "rb");
    uint32_t i;
    uint16_t b;

    if (file == NULL)
        return false;
    if (fseek(file, 0, SEEK_END) != 0 || ftell(file) != expected || fseek(file, 0, SEEK_SET) != 0) {
        fclose(file);
        return false;
    }
    for (i = 0; i < HOST_EEPROM_WORDS; i++) {
        uint16_t word = 0;
        for (b = 0; b < EEPROM_WORD_BYTES; b++)
            word = (uint16_t)(word | ((uint16_t)(fgetc(file) & BYTE_MASK) << (BITS_PER_BYTE * b)));
        board->eeprom[i] = word;
    }
    for (i = 0; i < HOST_FLASH_WORDS; i++) {
        uint32_t instruction = 0;
        for (b = 0; b < INSTRUCTION_BYTES; b++)
            instruction |= (uint32_t)(fgetc(file) & BYTE_MASK) << (BITS_PER_BYTE * b);
        board->flash[i] = instruction;
    }
    fclose(file);
    return true;
}
