// CRC-16/XMODEM as protocol.md §9 defines it (polynomial 0x1021, seed 0),
// one bit at a time: the tests' own, written independently of the
// firmware's node_crc16.

#pragma once

#include <cstdint>
#include <vector>

namespace bootloader_test
{

inline uint16_t crc_xmodem(const std::vector<uint8_t> &bytes)
{
    constexpr uint16_t polynomial = 0x1021, top_bit = 0x8000;
    uint16_t crc = 0;
    for (uint8_t byte : bytes) {
        crc ^= static_cast<uint16_t>(byte << 8);
        for (int bit = 0; bit < 8; bit++)
            crc = static_cast<uint16_t>((crc & top_bit) ? (crc << 1) ^ polynomial : crc << 1);
    }
    return crc;
}

} // namespace bootloader_test
