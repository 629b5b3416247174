// Aseba Studio's "save the binary code": the .abo file of a compiled program
// (aesl.md §6), which a loader checks against the robot before uploading.

#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tools/compiler/target.hpp"

namespace aseba::ide
{

// Who the program is for, beyond its description.
struct BinaryIdentity {
    uint16_t node_id = 0;
    uint16_t product_id = 0;       // the node's _productId, 0 if it has none
    uint16_t firmware_version = 0; // the node's _fwversion[0], 0 if it has none
};

// The description fingerprint of protocol.md §9.
uint16_t description_fingerprint(const TargetDescription &description);

// The bytes of the .abo file for `bytecode` compiled for `description`.
std::vector<uint8_t> binary_file(const TargetDescription &description,
                                 const BinaryIdentity &identity,
                                 const std::vector<uint16_t> &bytecode);

// `bytes` in base64 (RFC 4648, with padding), for JSON.
std::string base64(const std::vector<uint8_t> &bytes);

} // namespace aseba::ide
