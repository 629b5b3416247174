// Every binary and unary operator on the boundary values, in
// BINARY_ARITHMETIC, CONDITIONAL_BRANCH and UNARY_ARITHMETIC. The expected
// results follow bytecode.md §4 computed here in 64-bit integers: operands
// promoted, the operation done exactly, the result reduced modulo 2^16;
// shifts by the count modulo 32; division truncated toward zero.

#include <cstdint>
#include <optional>
#include <sstream>

#include <gtest/gtest.h>

#include "tests/support/assembler.hpp"
#include "tests/support/vm_harness.hpp"

extern "C" {
#include "vm/vm_opcodes.h"
}

namespace
{

using test_support::VmHarness;
using test_support::VmMessage;

const int64_t boundary_values[] = { -32768, -1, 0, 1, 32767 };
const int64_t shift_counts[] = { 0, 15, 16, 17, 31, 32, 33, -1, -16, -32768, 32767 };
const int64_t other_values[] = { -7, 7, 2, -2, 3, 200, 12345, -12345, 0x5555 };

constexpr uint16_t RESULT_ADDRESS = 40;

// The int16 that `value` becomes when only its low 16 bits are kept.
int64_t wrap16(int64_t value)
{
    int64_t low = ((value % 65536) + 65536) % 65536;
    return low >= 32768 ? low - 65536 : low;
}

int64_t floor_divide(int64_t a, int64_t b)
{
    int64_t quotient = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0)))
        quotient--;
    return quotient;
}

uint16_t bits(int64_t value)
{
    return static_cast<uint16_t>(wrap16(value) + 65536) & 0xFFFF;
}

// The result of `a op b` by §4.1, or nothing for a division by zero.
std::optional<int64_t> expected_binary(int op, int64_t a, int64_t b)
{
    int64_t count = ((b % 32) + 32) % 32; // the count as x86 takes it (§4.1)
    int64_t power = int64_t{ 1 } << count;
    switch (op) {
    case VM_BINARY_SHIFT_LEFT: return wrap16(a * power);
    case VM_BINARY_SHIFT_RIGHT: return wrap16(floor_divide(a, power));
    case VM_BINARY_ADD: return wrap16(a + b);
    case VM_BINARY_SUB: return wrap16(a - b);
    case VM_BINARY_MULT: return wrap16(a * b);
    case VM_BINARY_DIV:
        if (b == 0)
            return std::nullopt;
        return wrap16(a / b); // C++ division truncates toward zero, as §4.1 asks
    case VM_BINARY_MOD:
        if (b == 0)
            return std::nullopt;
        return wrap16(a - b * (a / b));
    case VM_BINARY_BIT_OR: return wrap16(bits(a) | bits(b));
    case VM_BINARY_BIT_XOR: return wrap16(bits(a) ^ bits(b));
    case VM_BINARY_BIT_AND: return wrap16(bits(a) & bits(b));
    case VM_BINARY_EQUAL: return a == b;
    case VM_BINARY_NOT_EQUAL: return a != b;
    case VM_BINARY_BIGGER_THAN: return a > b;
    case VM_BINARY_BIGGER_EQUAL_THAN: return a >= b;
    case VM_BINARY_SMALLER_THAN: return a < b;
    case VM_BINARY_SMALLER_EQUAL_THAN: return a <= b;
    case VM_BINARY_OR: return a != 0 || b != 0;
    case VM_BINARY_AND: return a != 0 && b != 0;
    }
    ADD_FAILURE() << "no rule for operator " << op;
    return 0;
}

std::vector<std::pair<int64_t, int64_t>> operand_pairs(int op)
{
    std::vector<int64_t> values(std::begin(boundary_values), std::end(boundary_values));
    values.insert(values.end(), std::begin(other_values), std::end(other_values));
    std::vector<std::pair<int64_t, int64_t>> pairs;
    for (int64_t a : values) {
        if (op == VM_BINARY_SHIFT_LEFT || op == VM_BINARY_SHIFT_RIGHT) {
            for (int64_t count : shift_counts)
                pairs.emplace_back(a, count);
        } else {
            for (int64_t b : values)
                pairs.emplace_back(a, b);
        }
    }
    return pairs;
}

// Runs `listing` as the init event of a fresh VM. The log keeps what RUN
// reports of a program the verifier refused, not its state answer.
void run_listing(VmHarness &harness, const std::string &listing)
{
    test_support::Program program = test_support::assemble(listing);
    harness.load(program.words);
    vm_command_run(&harness.vm);
    std::erase_if(harness.log, [](const VmMessage &m) { return m.kind == VmMessage::STATE; });
    vm_run(&harness.vm, 0);
}

std::string binary_operator_name(const testing::TestParamInfo<int> &parameter)
{
    return test_support::binary_operator_names()[parameter.param];
}

std::string unary_operator_name(const testing::TestParamInfo<int> &parameter)
{
    return test_support::unary_operator_names()[parameter.param];
}

class BinaryOperator : public testing::TestWithParam<int>
{
};

TEST_P(BinaryOperator, ArithmeticFollowsTheSpecRules)
{
    const int op = GetParam();
    const std::string name = test_support::binary_operator_names()[op];
    for (auto [a, b] : operand_pairs(op)) {
        SCOPED_TRACE(std::to_string(a) + " " + name + " " + std::to_string(b));
        std::ostringstream listing;
        listing << "event init start\nstart:\n"
                << "LARGE_IMMEDIATE " << a << "\nLARGE_IMMEDIATE " << b << "\n"
                << "BINARY_ARITHMETIC " << name << "\n" // at address 7
                << "STORE " << RESULT_ADDRESS << "\nSTOP\n";
        VmHarness harness;
        harness.variables()[RESULT_ADDRESS] = 99;
        run_listing(harness, listing.str());
        std::optional<int64_t> expected = expected_binary(op, a, b);
        if (expected) {
            EXPECT_EQ(harness.variables()[RESULT_ADDRESS], *expected);
            EXPECT_TRUE(harness.log.empty());
            EXPECT_EQ(harness.vm.flags, 0);
        } else {
            // §8.2: 0 is pushed, pc moves past the instruction, the VM stops.
            VmMessage error;
            error.kind = VmMessage::DIVISION_BY_ZERO;
            error.pc = 7;
            ASSERT_EQ(harness.log.size(), 1u);
            EXPECT_EQ(describe(harness.log[0]), describe(error));
            EXPECT_EQ(harness.vm.pc, 8);
            EXPECT_EQ(harness.vm.sp, 0);
            EXPECT_EQ(harness.stack()[0], 0);
            EXPECT_EQ(harness.vm.flags, VM_FLAG_STEP_BY_STEP);
            EXPECT_EQ(harness.variables()[RESULT_ADDRESS], 99);
        }
    }
}

TEST_P(BinaryOperator, BranchTakesTheTruePathWhenTheResultIsNotZero)
{
    const int op = GetParam();
    const std::string name = test_support::binary_operator_names()[op];
    for (auto [a, b] : operand_pairs(op)) {
        SCOPED_TRACE(std::to_string(a) + " " + name + " " + std::to_string(b));
        std::ostringstream listing;
        listing << "event init start\nstart:\n"
                << "LARGE_IMMEDIATE " << a << "\nLARGE_IMMEDIATE " << b << "\n"
                << "CONDITIONAL_BRANCH " << name << " false\n" // at address 7
                << "SMALL_IMMEDIATE 1\nSTORE " << RESULT_ADDRESS << "\nSTOP\n"
                << "false:\nSMALL_IMMEDIATE 2\nSTORE " << RESULT_ADDRESS << "\nSTOP\n";
        VmHarness harness;
        run_listing(harness, listing.str());
        std::optional<int64_t> expected = expected_binary(op, a, b);
        bool is_true = expected && *expected != 0;
        const uint16_t branch_word = harness.bytecode()[7];
        EXPECT_EQ((branch_word & VM_BRANCH_WAS_TRUE_BIT) != 0, is_true);
        if (expected) {
            EXPECT_EQ(harness.variables()[RESULT_ADDRESS], is_true ? 1 : 2);
            EXPECT_TRUE(harness.log.empty());
        } else {
            // The false path is taken (the result is 0), then the VM stops.
            ASSERT_EQ(harness.log.size(), 1u);
            EXPECT_EQ(describe(harness.log[0]), "error division_by_zero pc=7");
            EXPECT_EQ(harness.vm.flags, VM_FLAG_STEP_BY_STEP);
            EXPECT_EQ(harness.vm.sp, -1);
            EXPECT_EQ(harness.variables()[RESULT_ADDRESS], 0);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(AllOperators,
                         BinaryOperator,
                         testing::Range(0, static_cast<int>(VM_BINARY_OPERATOR_COUNT)),
                         binary_operator_name);

std::optional<int64_t> expected_unary(int op, int64_t v)
{
    switch (op) {
    case VM_UNARY_SUB: return wrap16(-v);
    case VM_UNARY_ABS: return wrap16(v < 0 ? -v : v);
    case VM_UNARY_BIT_NOT: return wrap16(~bits(v));
    }
    return std::nullopt; // NOT: never emitted, rejected by the VM
}

class UnaryOperator : public testing::TestWithParam<int>
{
};

TEST_P(UnaryOperator, ArithmeticFollowsTheSpecRules)
{
    const int op = GetParam();
    const std::string name = test_support::unary_operator_names()[op];
    std::vector<int64_t> values(std::begin(boundary_values), std::end(boundary_values));
    values.insert(values.end(), std::begin(other_values), std::end(other_values));
    for (int64_t v : values) {
        SCOPED_TRACE(name + " " + std::to_string(v));
        std::ostringstream listing;
        listing << "event init start\nstart:\nLARGE_IMMEDIATE " << v << "\n"
                << "UNARY_ARITHMETIC " << name << "\n" // at address 5
                << "STORE " << RESULT_ADDRESS << "\nSTOP\n";
        VmHarness harness;
        harness.variables()[RESULT_ADDRESS] = 99;
        run_listing(harness, listing.str());
        if (std::optional<int64_t> expected = expected_unary(op, v)) {
            EXPECT_EQ(harness.variables()[RESULT_ADDRESS], *expected);
            EXPECT_TRUE(harness.log.empty());
        } else {
            // Not a valid operator (§4.2): the program is refused, RUN
            // reports it at the instruction.
            ASSERT_EQ(harness.log.size(), 1u);
            EXPECT_EQ(harness.log[0].kind, VmMessage::NODE_ERROR);
            EXPECT_EQ(harness.log[0].pc, 5);
            EXPECT_EQ(harness.vm.flags, VM_FLAG_STEP_BY_STEP);
            EXPECT_EQ(harness.variables()[RESULT_ADDRESS], 99);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(AllOperators,
                         UnaryOperator,
                         testing::Range(0, static_cast<int>(VM_UNARY_OPERATOR_COUNT)),
                         unary_operator_name);

} // namespace
