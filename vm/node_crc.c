// CRC-16/XMODEM (node_crc.h).

#include "node_crc.h"

#define BYTE_BITS        8
#define CRC16_POLYNOMIAL 0x1021
#define CRC16_TOP_BIT    0x8000

uint16_t node_crc16(uint16_t crc, const uint8_t *bytes, uint16_t count)
{
    uint16_t i;
    uint8_t bit;

    for (i = 0; i < count; i++) {
        crc ^= (uint16_t)((uint16_t)bytes[i] << BYTE_BITS);
        for (bit = 0; bit < BYTE_BITS; bit++) {
            if (crc & CRC16_TOP_BIT)
                crc = (uint16_t)((uint16_t)(crc << 1) ^ CRC16_POLYNOMIAL);
            else
                crc = (uint16_t)(crc << 1);
        }
    }
    return crc;
}
