// Checks the application's descriptor and CRC before the bootloader starts it.

#include "bootloader/boot_application.h"

#include "vm/node.h"

#define PC_UNITS_PER_WORD 2u
#define BYTE_BITS         8u
#define BYTE_MASK         0xFFu
#define CRC16_MASK        0xFFFFul
#define INSTRUCTION_BYTES 3u

uint16_t boot_flash_crc(hal_board *board, uint32_t start, uint32_t end)
{
    uint16_t crc = 0;
    uint32_t address;

    for (address = start; address < end; address += PC_UNITS_PER_WORD) {
        uint32_t instruction = hal_flash_read(board, address);
        uint8_t bytes[INSTRUCTION_BYTES];
        bytes[0] = (uint8_t)(instruction & BYTE_MASK);
        bytes[1] = (uint8_t)((instruction >> BYTE_BITS) & BYTE_MASK);
        bytes[2] = (uint8_t)((instruction >> (2u * BYTE_BITS)) & BYTE_MASK);
        crc = node_crc16(crc, bytes, INSTRUCTION_BYTES);
    }
    return crc;
}

static uint32_t descriptor_word(hal_board *board, uint16_t index)
{
    return hal_flash_read(board, BOOT_DESCRIPTOR_ADDRESS + (uint32_t)index * PC_UNITS_PER_WORD);
}

bool boot_application_valid(hal_board *board, uint32_t *entry)
{
    uint32_t end = descriptor_word(board, BOOT_DESCRIPTOR_END_INDEX);
    uint32_t start_address = descriptor_word(board, BOOT_DESCRIPTOR_ENTRY_INDEX);
    uint32_t crc = descriptor_word(board, BOOT_DESCRIPTOR_CRC_INDEX);

    if (descriptor_word(board, BOOT_DESCRIPTOR_MAGIC_INDEX) != BOOT_DESCRIPTOR_MAGIC)
        return false;
    if (end <= BOOT_CHECKED_START || end > BOOT_DESCRIPTOR_ADDRESS || end % PC_UNITS_PER_WORD != 0)
        return false;
    if (start_address < BOOT_APPLICATION_START || start_address >= end ||
        start_address >= BOOT_ENTRY_LIMIT || start_address % PC_UNITS_PER_WORD != 0 ||
        crc > CRC16_MASK)
        return false;
    if (boot_flash_crc(board, BOOT_CHECKED_START, end) != (uint16_t)crc)
        return false;
    *entry = start_address;
    return true;
}
