// ports/dspic30/dspic30_runtime.c, the dsPIC's 32-bit helpers, against the
// host's own division, modulo and multiplication (C's rules: quotients
// truncate toward zero, a remainder has the dividend's sign), on the edge
// values and on a million seeded random pairs.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

extern "C" {
uint32_t dspic30_udivsi3(uint32_t dividend, uint32_t divisor);
uint32_t dspic30_umodsi3(uint32_t dividend, uint32_t divisor);
int32_t dspic30_divsi3(int32_t dividend, int32_t divisor);
int32_t dspic30_modsi3(int32_t dividend, int32_t divisor);
int32_t dspic30_mulsi3(int32_t a, int32_t b);
}

namespace
{

const std::vector<uint32_t> edges = { 0,          1,          2,          3,          7,
                                      0x7FFF,     0x8000,     0xFFFF,     0x10000,    0x12345678,
                                      0x7FFFFFFF, 0x80000000, 0x80000001, 0xFFFFFFFE, 0xFFFFFFFF };

void expect_same(uint32_t x, uint32_t y)
{
    const int32_t a = static_cast<int32_t>(x), b = static_cast<int32_t>(y);
    EXPECT_EQ(dspic30_mulsi3(a, b), static_cast<int32_t>(x * y)) << x << " * " << y;
    if (y == 0)
        return;
    EXPECT_EQ(dspic30_udivsi3(x, y), x / y) << x << " / " << y;
    EXPECT_EQ(dspic30_umodsi3(x, y), x % y) << x << " % " << y;
    if (a == INT32_MIN && b == -1) // overflows in C; the helper wraps
        return;
    EXPECT_EQ(dspic30_divsi3(a, b), a / b) << a << " / " << b;
    EXPECT_EQ(dspic30_modsi3(a, b), a % b) << a << " % " << b;
}

} // namespace

TEST(Dspic30Runtime, EdgeValuesGiveTheHostsResults)
{
    for (uint32_t x : edges)
        for (uint32_t y : edges)
            expect_same(x, y);
}

TEST(Dspic30Runtime, RandomPairsGiveTheHostsResults)
{
    std::mt19937 random(20261127);
    for (int i = 0; i < 1'000'000; ++i) {
        uint32_t x = random(), y = random();
        // Small divisors too, where the quotient has many bits.
        expect_same(x, i % 2 ? y : y >> (y % 32));
        if (HasFailure())
            return;
    }
}

TEST(Dspic30Runtime, DivisionByZeroNeitherTrapsNorHangs)
{
    EXPECT_EQ(dspic30_udivsi3(1234, 0), UINT32_MAX);
    EXPECT_EQ(dspic30_umodsi3(1234, 0), 1234u);
    EXPECT_EQ(dspic30_divsi3(-5, 0), 1); // -(all ones): the quotient's sign rule
    EXPECT_EQ(dspic30_modsi3(-5, 0), -5);
}

TEST(Dspic30Runtime, MostNegativeOverMinusOneWraps)
{
    EXPECT_EQ(dspic30_divsi3(INT32_MIN, -1), INT32_MIN);
    EXPECT_EQ(dspic30_modsi3(INT32_MIN, -1), 0);
}
