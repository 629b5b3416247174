// CRC-16/XMODEM, shared by the node's description fingerprint (protocol.md
// §9), the bytecode store's records and the bootloader's check of the
// application. A unit of its own, which needs nothing of the node, so that
// the store, the bootloader and the flash tools link the CRC alone.

#ifndef NODE_CRC_H
#define NODE_CRC_H

#include <stdint.h>

// CRC-16/XMODEM (polynomial 0x1021, initial 0) of `count` bytes, continued
// from `crc`.
uint16_t node_crc16(uint16_t crc, const uint8_t *bytes, uint16_t count);

#endif
