/* Constants in program memory read through the PSV window: tables of
   several widths, strings, and a table of pointers to strings. */

#include "harness.h"

static const uint16_t words[] = { 0x0001, 0x0203, 0x0405, 0x0607, 0xFFFF, 0x8000, 0x7FFF, 0x1234,
                                  0xABCD, 0x5A5A, 0x0F0F, 0xF0F0, 0x1111, 0x2222, 0x3333, 0x4444 };
static const int8_t bytes[] = { -128, -1, 0, 1, 127, 42, -42, 99 };
static const uint32_t longs[] = { 0xDEADBEEFu, 0x00000001u, 0x80000000u, 0x12345678u };
static const char *const names[] = { "alpha", "beta", "gamma", "delta", "" };
static volatile uint16_t index_base = 0;

void differential_main(void)
{
    uint32_t h = 0;
    for (uint16_t i = index_base; i < sizeof words / sizeof words[0]; i++)
        h = h * 65599u + words[i];
    report("words", h);

    h = 0;
    for (uint16_t i = index_base; i < sizeof bytes; i++)
        h = h * 33u + (uint32_t)(int32_t)bytes[i];
    report("bytes", h);

    h = 0;
    for (uint16_t i = index_base; i < 4; i++)
        h ^= longs[i] + i;
    report("longs", h);

    h = 0;
    for (uint16_t i = index_base; i < 5; i++)
        for (const char *p = names[i]; *p; p++)
            h = h * 131u + (uint8_t)*p;
    report("strings", h);
}
