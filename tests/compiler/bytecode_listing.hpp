// A human-readable listing of protocol-5 bytecode (bytecode.md §2-§4), printed
// by the compiler tests when two compilations differ.

#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace compiler_tests
{

// One line per instruction: address, raw words, mnemonic and operands; the
// event table first. Words that do not decode are listed as such.
std::string bytecode_listing(const std::vector<uint16_t> &bytecode);

// Two listings side by side under their titles, differing lines marked '!'.
std::string compare_listings(const std::vector<uint16_t> &left,
                             const std::vector<uint16_t> &right,
                             const std::string &left_title = "ours",
                             const std::string &right_title = "reference");

} // namespace compiler_tests
