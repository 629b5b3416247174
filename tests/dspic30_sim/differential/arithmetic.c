/* 8-, 16- and 32-bit arithmetic, division and modulo (signed and unsigned),
   shifts and comparisons over a table of inputs; the inputs are volatile so
   that the dsPIC computes at run time. Where C promotes to int, the
   expressions keep within 16 bits or go through unsigned types, as int is
   16 bits on the dsPIC and 32 on the host. */

#include "harness.h"

static volatile uint32_t inputs[] = { 0u,          1u,          2u,          3u,
                                      7u,          0x7Fu,       0x80u,       0xFFu,
                                      0x100u,      0x1234u,     0x7FFFu,     0x8000u,
                                      0x8001u,     0xFFFEu,     0xFFFFu,     0x10000u,
                                      0x12345678u, 0x7FFFFFFFu, 0x80000000u, 0xFFFFFFFFu,
                                      0xDEADBEEFu, 0x00C0FFEEu, 0x55555555u, 0xAAAAAAABu };
#define COUNT (sizeof inputs / sizeof inputs[0])

static uint32_t mix(uint32_t h, uint32_t v)
{
    return (h ^ v) * 16777619u;
}

static void eight_bit(void)
{
    uint32_t h = 2166136261u;
    for (unsigned i = 0; i < COUNT; i++)
        for (unsigned j = 0; j < COUNT; j++) {
            uint8_t a = (uint8_t)inputs[i], b = (uint8_t)inputs[j];
            int8_t sa = (int8_t)a, sb = (int8_t)b;
            h = mix(h, (uint8_t)(a + b));
            h = mix(h, (uint8_t)(a - b));
            h = mix(
              h, (uint8_t)((unsigned)a * b)); /* uint8_t * uint8_t is a 16-bit int on the dsPIC */
            h = mix(h, (uint32_t)(uint8_t)(a & b) | (uint32_t)(uint8_t)(a ^ b) << 8);
            h = mix(h, (uint32_t)(a < b) | (uint32_t)(sa < sb) << 1 | (uint32_t)(a == b) << 2);
            if (b != 0) {
                h = mix(h, (uint8_t)(a / b));
                h = mix(h, (uint8_t)(a % b));
                if (!(sa == -128 && sb == -1)) {
                    h = mix(h, (uint32_t)(int32_t)(int8_t)(sa / sb));
                    h = mix(h, (uint32_t)(int32_t)(int8_t)(sa % sb));
                }
            }
            h = mix(h, (uint8_t)(a >> (b & 7)));
            h = mix(h, (uint32_t)(int32_t)(int8_t)(sa >> (b & 7)));
        }
    report("eight_bit", h);
}

static void sixteen_bit(void)
{
    uint32_t h = 2166136261u;
    for (unsigned i = 0; i < COUNT; i++)
        for (unsigned j = 0; j < COUNT; j++) {
            uint16_t a = (uint16_t)inputs[i], b = (uint16_t)inputs[j];
            int16_t sa = (int16_t)a, sb = (int16_t)b;
            h = mix(h, (uint16_t)(a + b));
            h = mix(h, (uint16_t)(a - b));
            h = mix(h, (uint16_t)((uint32_t)a * b));
            h = mix(h, (uint32_t)((int32_t)sa * sb));
            h = mix(h, (uint32_t)a * b);
            h = mix(h, (uint16_t)(a | b) ^ (uint16_t)~a);
            h = mix(h,
                    (uint32_t)(a < b) | (uint32_t)(sa < sb) << 1 | (uint32_t)(a <= b) << 2 |
                      (uint32_t)(sa >= sb) << 3 | (uint32_t)(a != b) << 4);
            if (b != 0) {
                h = mix(h, (uint16_t)(a / b));
                h = mix(h, (uint16_t)(a % b));
                if (!(sa == -32768 && sb == -1)) {
                    h = mix(h, (uint32_t)(int32_t)(int16_t)(sa / sb));
                    h = mix(h, (uint32_t)(int32_t)(int16_t)(sa % sb));
                }
            }
            h = mix(h, (uint16_t)(a << (b & 15)));
            h = mix(h, (uint16_t)(a >> (b & 15)));
            h = mix(h, (uint32_t)(int32_t)(int16_t)(sa >> (b & 15)));
        }
    report("sixteen_bit", h);
}

static void thirty_two_bit(void)
{
    uint32_t h = 2166136261u;
    for (unsigned i = 0; i < COUNT; i++)
        for (unsigned j = 0; j < COUNT; j++) {
            uint32_t a = inputs[i], b = inputs[j];
            int32_t sa = (int32_t)a, sb = (int32_t)b;
            h = mix(h, a + b);
            h = mix(h, a - b);
            h = mix(h, a * b);
            h = mix(h, (a & ~b) | (a ^ b));
            h = mix(h,
                    (uint32_t)(a < b) | (uint32_t)(sa < sb) << 1 | (uint32_t)(a > b) << 2 |
                      (uint32_t)(sa <= sb) << 3);
            if (b != 0) {
                h = mix(h, a / b);
                h = mix(h, a % b);
                if (!(sa == INT32_MIN && sb == -1)) {
                    h = mix(h, (uint32_t)(sa / sb));
                    h = mix(h, (uint32_t)(sa % sb));
                }
            }
            h = mix(h, a << (b & 31));
            h = mix(h, a >> (b & 31));
            h = mix(h, (uint32_t)(sa >> (b & 31)));
        }
    report("thirty_two_bit", h);
}

void differential_main(void)
{
    eight_bit();
    sixteen_bit();
    thirty_two_bit();
}
