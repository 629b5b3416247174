// The run-time helpers that GCC calls for the dsPIC30F where the core has
// no instruction: 32-bit division and modulo (the DIV instructions divide
// 32 bits by 16 only) and 32-bit multiplication. Microchip's libpic30 has
// them; the GPL toolchain does not, so the port brings its own, and XC16
// users link these too. `pic30-elf-nm -u` on the objects lists what GCC
// asks for; 64-bit arithmetic is kept out of the firmware instead.
//
// The names and the results are GCC's (its libgcc documentation, "Routines
// for integer arithmetic"): quotients truncate toward zero, a remainder has
// the sign of the dividend. Division by zero is undefined in C; here it
// gives an all-ones quotient and the dividend as remainder, without a trap.
//
// The host tests compile this file with the names mapped to others
// (tests/ports/dspic30/module.mk) and compare it with the host's own arithmetic.

#include <stdint.h>

// Declared here: GCC calls them, no header of the project does.
uint32_t __udivsi3(uint32_t dividend, uint32_t divisor);
uint32_t __umodsi3(uint32_t dividend, uint32_t divisor);
int32_t __divsi3(int32_t dividend, int32_t divisor);
int32_t __modsi3(int32_t dividend, int32_t divisor);
int32_t __mulsi3(int32_t a, int32_t b);

#define WORD_BITS 32u

// Restoring division, one quotient bit per step, the remainder in
// *remainder. Shift and subtract only: nothing here calls back into a helper.
static uint32_t divide(uint32_t dividend, uint32_t divisor, uint32_t *remainder)
{
    uint32_t quotient = 0;
    uint32_t rest = 0;

    if (divisor == 0) {
        *remainder = dividend;
        return UINT32_MAX;
    }
    for (uint16_t bit = 0; bit < WORD_BITS; bit++) {
        rest = (rest << 1) | (dividend >> (WORD_BITS - 1u));
        dividend <<= 1;
        quotient <<= 1;
        if (rest >= divisor) {
            rest -= divisor;
            quotient |= 1u;
        }
    }
    *remainder = rest;
    return quotient;
}

// |value| as an unsigned number (INT32_MIN included).
static uint32_t magnitude(int32_t value)
{
    return value < 0 ? 0u - (uint32_t)value : (uint32_t)value;
}

uint32_t __udivsi3(uint32_t dividend, uint32_t divisor)
{
    uint32_t remainder;
    return divide(dividend, divisor, &remainder);
}

uint32_t __umodsi3(uint32_t dividend, uint32_t divisor)
{
    uint32_t remainder;
    divide(dividend, divisor, &remainder);
    return remainder;
}

int32_t __divsi3(int32_t dividend, int32_t divisor)
{
    uint32_t remainder;
    uint32_t quotient = divide(magnitude(dividend), magnitude(divisor), &remainder);
    // Two's complement wrap-around for INT32_MIN / -1, as the hardware would.
    return (int32_t)((dividend < 0) != (divisor < 0) ? 0u - quotient : quotient);
}

int32_t __modsi3(int32_t dividend, int32_t divisor)
{
    uint32_t remainder;
    divide(magnitude(dividend), magnitude(divisor), &remainder);
    return (int32_t)(dividend < 0 ? 0u - remainder : remainder);
}

// The low 32 bits of the product, from three 16 x 16 products (the high
// halves' product only moves bits above 32).
int32_t __mulsi3(int32_t a, int32_t b)
{
    uint32_t x = (uint32_t)a, y = (uint32_t)b;
    uint16_t x_low = (uint16_t)x, x_high = (uint16_t)(x >> 16);
    uint16_t y_low = (uint16_t)y, y_high = (uint16_t)(y >> 16);
    uint32_t low = (uint32_t)x_low * y_low;
    uint16_t cross = (uint16_t)((uint32_t)x_low * y_high + (uint32_t)x_high * y_low);
    return (int32_t)(low + ((uint32_t)cross << 16));
}
