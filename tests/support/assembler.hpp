// A small assembler for Aseba bytecode, for tests: turns a readable listing
// into the words a VM runs. Mnemonics are the names of the lists in
// vm/vm_opcodes.h, so the tests and the VM share one source of names.
//
// Syntax, one statement per line (`;` and `#` start comments):
//
//   event init start          event table entry: `init`, or an id (0xFFFE),
//   event 0 handler            then a label or an address
//   start:                     a label (may share a line with an instruction)
//   SMALL_IMMEDIATE -5         operands: decimal, 0x hex, negative
//   LOAD_INDIRECT 36 4         base, size
//   UNARY_ARITHMETIC SUB       operator names of VM_UNARY_OPERATOR_LIST
//   BINARY_ARITHMETIC ADD      operator names of VM_BINARY_OPERATOR_LIST
//   JUMP loop                  label (made relative) or a raw displacement
//   CONDITIONAL_BRANCH BIGGER_THAN done when    `when` sets the is-when bit,
//                                                `was_true` the was-true bit
//   EMIT 0 37 2                event id, address, length
//   SUB_CALL clear             label or absolute address
//   .word 0xF000 label         raw words (a label gives its address)
//   .raw                       no event table: the listing is the whole image
//
// Mnemonics and operator names are case-insensitive. Unless `.raw` is given,
// the image starts with the table of the `event` lines (word 0 = 2E + 1).

#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace test_support
{

struct AssemblyError : std::runtime_error {
    AssemblyError(unsigned line, const std::string &message);
    unsigned line; // 1-based line of the listing
};

struct Program {
    std::vector<uint16_t> words;
    std::map<std::string, uint16_t> labels; // label name -> absolute address
};

// Assembles `listing`; throws AssemblyError naming the line of the first
// mistake (unknown mnemonic, bad operand, undefined or duplicate label).
Program assemble(std::string_view listing);

// Names from vm/vm_opcodes.h, for tests that build listings programmatically.
const std::vector<std::string> &binary_operator_names(); // indexed by code
const std::vector<std::string> &unary_operator_names();  // indexed by code

} // namespace test_support
