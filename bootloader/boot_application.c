// Checks the application's descriptor and CRC before the bootloader starts it.

#include "bootloader/boot_application.h"

#include "vm/node_crc.h"

#define BYTE_BITS  8u
#define BYTE_MASK  0xFFu
#define CRC16_MASK 0xFFFFul
#define WORD_BYTES (HAL_FLASH_WORD_BITS / BYTE_BITS)

uint16_t boot_flash_crc(hal_board *board, uint32_t start, uint32_t end)
{
    uint16_t crc = 0;
    uint32_t address;

    for (address = start; address < end; address += HAL_FLASH_WORD_SPAN) {
        uint32_t word = hal_flash_read(board, address);
        uint8_t bytes[WORD_BYTES];
        uint16_t i;
        for (i = 0; i < WORD_BYTES; i++)
            bytes[i] = (uint8_t)((word >> (BYTE_BITS * i)) & BYTE_MASK);
        crc = node_crc16(crc, bytes, WORD_BYTES);
    }
    return crc;
}

static uint32_t descriptor_word(hal_board *board, uint16_t index)
{
    return hal_flash_read(board, BOOT_DESCRIPTOR_ADDRESS + (uint32_t)index * HAL_FLASH_WORD_SPAN);
}

bool boot_application_valid(hal_board *board, uint32_t *entry)
{
    uint32_t end = descriptor_word(board, BOOT_DESCRIPTOR_END_INDEX);
    uint32_t start_address = descriptor_word(board, BOOT_DESCRIPTOR_ENTRY_INDEX);
    uint32_t crc = descriptor_word(board, BOOT_DESCRIPTOR_CRC_INDEX);

    if (descriptor_word(board, BOOT_DESCRIPTOR_MAGIC_INDEX) != BOOT_DESCRIPTOR_MAGIC)
        return false;
    if (end <= BOOT_CHECKED_START || end > BOOT_DESCRIPTOR_ADDRESS ||
        end % HAL_FLASH_WORD_SPAN != 0)
        return false;
    if (start_address < BOOT_APPLICATION_START || start_address >= end ||
        start_address >= BOOT_ENTRY_LIMIT || start_address % HAL_FLASH_WORD_SPAN != 0 ||
        crc > CRC16_MASK)
        return false;
    if (boot_flash_crc(board, BOOT_CHECKED_START, end) != (uint16_t)crc)
        return false;
    *entry = start_address;
    return true;
}
