// The test assembler itself: the worked examples of bytecode.md §10 written
// with mnemonics must give the words of the spec's tables, and mistakes in a
// listing must be reported with their line.

#include <gtest/gtest.h>

#include "tests/support/assembler.hpp"

namespace
{

using test_support::assemble;
using test_support::AssemblyError;

TEST(Assembler, WorkedExampleOneGivesTheSpecWords)
{
    const char listing[] = R"(
event 0xFFFE timer
event init init
timer:
    LOAD 36
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 36
    LOAD 36
    SMALL_IMMEDIATE 5
    CONDITIONAL_BRANCH BIGGER_THAN end when
    EMIT 0 37 2
end: STOP
init:
    SMALL_IMMEDIATE 0
    STORE 36
    SMALL_IMMEDIATE 10
    STORE 37
    LARGE_IMMEDIATE -3000
    STORE 38
    STOP
)";
    const std::vector<uint16_t> spec = { 0x0005, 0xFFFE, 0x0005, 0xFFFF, 0x0011, 0x3024, 0x1001,
                                         0x8002, 0x4024, 0x3024, 0x1005, 0xA10C, 0x0005, 0xB000,
                                         0x0025, 0x0002, 0x0000, 0x1000, 0x4024, 0x100A, 0x4025,
                                         0x2000, 0xF448, 0x4026, 0x0000 };
    test_support::Program program = assemble(listing);
    EXPECT_EQ(program.words, spec);
    EXPECT_EQ(program.labels.at("init"), 17);
}

TEST(Assembler, WorkedExampleTwoGivesTheSpecWords)
{
    const char listing[] = R"(
event 0 ping
ping:
    LOAD 2
    SMALL_IMMEDIATE 3
    binary_arithmetic div       ; names are case-insensitive
    LOAD 40
    STORE_INDIRECT 36 4
    LOAD 40
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    SMALL_IMMEDIATE 4
    BINARY_ARITHMETIC MOD
    STORE 40
    SMALL_IMMEDIATE 4
    SMALL_IMMEDIATE 41
    SMALL_IMMEDIATE 41
    SMALL_IMMEDIATE 41
    SMALL_IMMEDIATE 36
    NATIVE_CALL 11
    SUB_CALL clear
    STOP
clear:
    SMALL_IMMEDIATE 4
    SMALL_IMMEDIATE 0
    STORE 1059
    SMALL_IMMEDIATE 1059
    SMALL_IMMEDIATE 36
    NATIVE_CALL 1
    SUB_RET
)";
    const std::vector<uint16_t> spec = { 0x0003, 0x0000, 0x0003, 0x3002, 0x1003, 0x8005,
                                         0x3028, 0x6024, 0x0004, 0x3028, 0x1001, 0x8002,
                                         0x1004, 0x8006, 0x4028, 0x1004, 0x1029, 0x1029,
                                         0x1029, 0x1024, 0xC00B, 0xD017, 0x0000, 0x1004,
                                         0x1000, 0x4423, 0x1423, 0x1024, 0xC001, 0xE000 };
    EXPECT_EQ(assemble(listing).words, spec);
}

TEST(Assembler, EncodesOperandsAndFlags)
{
    test_support::Program program = assemble(R"(
.raw
top: SMALL_IMMEDIATE -2048
     SMALL_IMMEDIATE 0x7FF
     LARGE_IMMEDIATE 0xFFFF
     UNARY_ARITHMETIC ABS
     JUMP top
     CONDITIONAL_BRANCH 17 top was_true when
     JUMP -1
     .word -1 top 0x1234 here
here:
)");
    const std::vector<uint16_t> expected = { 0x1800, 0x17FF, 0x2000, 0xFFFF, 0x7001, 0x9FFB, 0xA311,
                                             0xFFFA, 0x9FFF, 0xFFFF, 0x0000, 0x1234, 0x000D };
    EXPECT_EQ(program.words, expected);
}

TEST(Assembler, ReportsMistakesWithTheirLine)
{
    const std::pair<const char *, unsigned> mistakes[] = {
        { "STOP\nFROB 1\n", 2 },
        { "JUMP nowhere\n", 1 },
        { "a: STOP\n\na: STOP\n", 3 },
        { "SMALL_IMMEDIATE 2048\n", 1 },
        { "LOAD 4096\n", 1 },
        { "BINARY_ARITHMETIC POWER\n", 1 },
        { "EMIT 1 2\n", 1 },
        { "CONDITIONAL_BRANCH EQUAL x sometimes\nx: STOP\n", 1 },
        { "SMALL_IMMEDIATE 12z\n", 1 },
    };
    for (auto [listing, line] : mistakes) {
        SCOPED_TRACE(listing);
        try {
            assemble(listing);
            ADD_FAILURE() << "accepted";
        } catch (const AssemblyError &error) {
            EXPECT_EQ(error.line, line) << error.what();
        }
    }
}

} // namespace
