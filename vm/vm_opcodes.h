// The Aseba bytecode (protocol 5): one list of opcodes and operators, used by
// the interpreter, the disassembler, the verifier and the compiler alike.
//
// Every instruction starts with one 16-bit word; the opcode is its top nibble:
//
//    15    12 11     10  9       8        7                     0
//   +--------+-------------------------------------------------------+
//   | opcode |                 operand (12 bits)                      |
//   +--------+-------------------------------------------------------+
//   | 0x7/8  |   0   0   0       0     |  operator (§4)               |
//   | 0xA    |   0   0 | was  | is     |  binary operator             |
//   |        |         | true | when   |                              |
//   +--------+-------------------------------------------------------+
//
// and is followed by 0, 1 or 2 operand words depending on the opcode alone.
// Signed 12-bit operands (small immediates, jump displacements) are two's
// complement; displacements are relative to the instruction's first word.

#ifndef VM_OPCODES_H
#define VM_OPCODES_H

#include <stdint.h>

// VM_OPCODE(name, code, words, (pops, pushes), meaning): the stack words an
// instruction needs and those it leaves. NATIVE_CALL pops what its native
// takes; SUB_CALL and SUB_RET count nothing, because the callee runs on a
// stack of its own above the return address (see vm_verify.c).
#define VM_OPCODE_LIST(X)                                                                          \
    X(STOP, 0x0, 1, (0, 0), "end the event")                                                       \
    X(SMALL_IMMEDIATE, 0x1, 1, (0, 1), "push the signed 12-bit operand")                           \
    X(LARGE_IMMEDIATE, 0x2, 2, (0, 1), "push word 1")                                              \
    X(LOAD, 0x3, 1, (0, 1), "push V[operand]")                                                     \
    X(STORE, 0x4, 1, (1, 0), "V[operand] = pop")                                                   \
    X(LOAD_INDIRECT, 0x5, 2, (1, 1), "S[top] = V[operand + S[top]], index checked against word 1") \
    X(STORE_INDIRECT, 0x6, 2, (2, 0), "V[operand + pop] = pop, index checked against word 1")      \
    X(UNARY_ARITHMETIC, 0x7, 1, (1, 1), "S[top] = op S[top]")                                      \
    X(BINARY_ARITHMETIC, 0x8, 1, (2, 1), "a = S[top-1], b = pop: S[top] = a op b")                 \
    X(JUMP, 0x9, 1, (0, 0), "pc += signed operand")                                                \
    X(CONDITIONAL_BRANCH, 0xA, 2, (2, 0), "if not (a op b) pc += word 1, else pc += 2")            \
    X(EMIT, 0xB, 3, (0, 0), "send event operand with V[word 1 ...] of word 2 words")               \
    X(NATIVE_CALL, 0xC, 1, (0, 0), "call native function operand; it pops its arguments")          \
    X(SUB_CALL, 0xD, 1, (0, 0), "push pc + 1, pc = operand")                                       \
    X(SUB_RET, 0xE, 1, (0, 0), "pc = pop")

enum vm_opcode {
#define VM_OPCODE_ENUM(name, code, words, stack, meaning) VM_OP_##name = code,
    VM_OPCODE_LIST(VM_OPCODE_ENUM)
#undef VM_OPCODE_ENUM
      VM_OP_INVALID = 0xF // never produced by a compiler: the verifier refuses it
};

// Binary operators (bits 7..0 of BINARY_ARITHMETIC and CONDITIONAL_BRANCH):
// VM_BINARY(name, code, source token). Results are computed on the operands
// promoted to 32 bits and truncated to 16; comparisons are signed.
#define VM_BINARY_OPERATOR_LIST(X)                                                                 \
    X(SHIFT_LEFT, 0, "<<")                                                                         \
    X(SHIFT_RIGHT, 1, ">>")                                                                        \
    X(ADD, 2, "+")                                                                                 \
    X(SUB, 3, "-")                                                                                 \
    X(MULT, 4, "*")                                                                                \
    X(DIV, 5, "/")                                                                                 \
    X(MOD, 6, "%")                                                                                 \
    X(BIT_OR, 7, "|")                                                                              \
    X(BIT_XOR, 8, "^")                                                                             \
    X(BIT_AND, 9, "&")                                                                             \
    X(EQUAL, 10, "==")                                                                             \
    X(NOT_EQUAL, 11, "!=")                                                                         \
    X(BIGGER_THAN, 12, ">")                                                                        \
    X(BIGGER_EQUAL_THAN, 13, ">=")                                                                 \
    X(SMALLER_THAN, 14, "<")                                                                       \
    X(SMALLER_EQUAL_THAN, 15, "<=")                                                                \
    X(OR, 16, "or")                                                                                \
    X(AND, 17, "and")

enum vm_binary_operator {
#define VM_BINARY_ENUM(name, code, token) VM_BINARY_##name = code,
    VM_BINARY_OPERATOR_LIST(VM_BINARY_ENUM)
#undef VM_BINARY_ENUM
      VM_BINARY_OPERATOR_COUNT
};

// Unary operators (bits 7..0 of UNARY_ARITHMETIC). NOT exists only inside the
// compiler (it is removed by De Morgan's laws); the VM rejects it.
#define VM_UNARY_OPERATOR_LIST(X)                                                                  \
    X(SUB, 0, "-")                                                                                 \
    X(ABS, 1, "abs")                                                                               \
    X(BIT_NOT, 2, "~")                                                                             \
    X(NOT, 3, "not")

enum vm_unary_operator {
#define VM_UNARY_ENUM(name, code, token) VM_UNARY_##name = code,
    VM_UNARY_OPERATOR_LIST(VM_UNARY_ENUM)
#undef VM_UNARY_ENUM
      VM_UNARY_OPERATOR_COUNT
};

#define VM_OPCODE_SHIFT          12
#define VM_OPERAND_MASK          0x0FFF
#define VM_OPERATOR_MASK         0x00FF
#define VM_BRANCH_IS_WHEN_BIT    0x0100
#define VM_BRANCH_WAS_TRUE_BIT   0x0200
#define VM_SMALL_IMMEDIATE_LIMIT 2048 // |v| < limit fits in the 12-bit operand

// Number of words of the instruction that starts with `word`.
static inline uint16_t vm_instruction_words(uint16_t word)
{
    switch (word >> VM_OPCODE_SHIFT) {
#define VM_OPCODE_WORDS(name, code, words, stack, meaning)                                         \
    case code: return words;
        VM_OPCODE_LIST(VM_OPCODE_WORDS)
#undef VM_OPCODE_WORDS
    default: return 1;
    }
}

// Event ids of the event vector table (bytecode[0] = table size, then pairs).
#define VM_EVENT_INIT        0xFFFF
#define VM_EVENT_LOCAL_FIRST 0xFFFE // local event i has id VM_EVENT_LOCAL_FIRST - i

#endif
