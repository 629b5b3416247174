/* Control flow and data layout: dense and sparse switch statements (jump
   tables), calls through function pointers, recursion, struct copies and
   structs passed and returned by value, arrays of structs. */

#include "harness.h"

static volatile uint16_t seeds[] = {
    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 100, 1000, 40000u
};
#define COUNT (sizeof seeds / sizeof seeds[0])

static uint16_t dense(uint16_t v)
{
    switch (v) {
    case 0: return 11;
    case 1: return 23;
    case 2: return 37;
    case 3: return 41;
    case 4: return 59;
    case 5: return 61;
    case 6: return 73;
    case 7: return 89;
    case 8: return 97;
    case 9: return 101;
    default: return 7;
    }
}

static uint16_t sparse(uint16_t v)
{
    switch (v) {
    case 3: return 1;
    case 13: return 2;
    case 100: return 3;
    case 1000: return 4;
    case 40000u: return 5;
    default: return 0;
    }
}

static uint16_t twice(uint16_t v)
{
    return (uint16_t)(v * 2u);
}
static uint16_t square(uint16_t v)
{
    return (uint16_t)((uint32_t)v * v);
}
static uint16_t negate(uint16_t v)
{
    return (uint16_t)(0u - v);
}
static uint16_t (*const operations[])(uint16_t) = { twice, square, negate, dense, sparse };

static uint32_t fibonacci(uint16_t n)
{
    return n < 2 ? n : fibonacci((uint16_t)(n - 1)) + fibonacci((uint16_t)(n - 2));
}

struct record {
    uint8_t tag;
    int16_t values[5];
    uint32_t total;
    char name[7];
};

static struct record make(uint16_t seed)
{
    struct record r;
    r.tag = (uint8_t)(seed * 3u);
    for (int i = 0; i < 5; i++)
        r.values[i] = (int16_t)(seed * 257u + (uint16_t)i);
    r.total = 0;
    for (int i = 0; i < 6; i++)
        r.name[i] = (char)('a' + (seed + i) % 26);
    r.name[6] = 0;
    return r;
}

static uint32_t digest(struct record r)
{
    uint32_t h = r.tag;
    for (int i = 0; i < 5; i++)
        h = h * 31u + (uint16_t)r.values[i];
    for (int i = 0; r.name[i]; i++)
        h = h * 31u + (uint8_t)r.name[i];
    return h + r.total;
}

void differential_main(void)
{
    uint32_t h = 0;
    for (unsigned i = 0; i < COUNT; i++)
        h = h * 131u + dense(seeds[i]) + (uint32_t)sparse(seeds[i]) * 1000u;
    report("switches", h);

    h = 0;
    for (unsigned i = 0; i < COUNT; i++)
        for (unsigned k = 0; k < sizeof operations / sizeof operations[0]; k++)
            h = h * 31u + operations[k](seeds[i]);
    report("function_pointers", h);

    report("recursion", fibonacci(seeds[12] + 7u));

    struct record table[4];
    for (unsigned i = 0; i < 4; i++)
        table[i] = make(seeds[i + 5]);
    struct record copy = table[2];
    copy.total = 12345;
    table[3] = copy;
    h = 0;
    for (unsigned i = 0; i < 4; i++)
        h = h * 7u + digest(table[i]);
    report("structs", h);
}
