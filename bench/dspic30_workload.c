/* The workload of bench-dspic30-sim: integer work of the kind the e-puck
   firmware does (a CRC over a buffer, a small insertion sort, 16- and
   32-bit arithmetic, a fixed-point filter, calls through a pointer), in an
   endless loop. Built with pic30-elf-gcc -Os for the dsPIC30F6014A by
   bench/module.mk; the benchmark runs it for a fixed number of cycles. */

#include <stdint.h>

#define BUFFER_SIZE 64
#define TAPS        8

static uint8_t buffer[BUFFER_SIZE];
static int16_t samples[BUFFER_SIZE];
static const int16_t coefficients[TAPS] = { 1024, -2048, 4096, 8192, 8192, 4096, -2048, 1024 };
volatile uint32_t sink;

static uint16_t crc16(const uint8_t *data, uint16_t length)
{
    uint16_t crc = 0xFFFF;
    while (length--) {
        crc ^= (uint16_t)*data++ << 8;
        for (uint8_t bit = 0; bit < 8; bit++)
            crc = (crc & 0x8000) ? (uint16_t)((crc << 1) ^ 0x1021) : (uint16_t)(crc << 1);
    }
    return crc;
}

static void sort(int16_t *values, uint16_t count)
{
    for (uint16_t i = 1; i < count; i++) {
        int16_t v = values[i];
        uint16_t j = i;
        while (j > 0 && values[j - 1] > v) {
            values[j] = values[j - 1];
            j--;
        }
        values[j] = v;
    }
}

static int32_t filter(const int16_t *x)
{
    int32_t acc = 0;
    for (uint16_t k = 0; k < TAPS; k++)
        acc += (int32_t)x[k] * coefficients[k];
    return acc >> 15;
}

static uint32_t mix(uint32_t a, uint32_t b)
{
    return (a * 2654435761u) ^ (b >> 3) ^ (a / (b | 1));
}

typedef uint32_t (*mixer)(uint32_t, uint32_t);

int main(void)
{
    volatile mixer m = mix;
    uint32_t state = 1;
    for (;;) {
        for (uint16_t i = 0; i < BUFFER_SIZE; i++) {
            state = state * 1103515245u + 12345u;
            buffer[i] = (uint8_t)(state >> 16);
            samples[i] = (int16_t)(state >> 8);
        }
        uint32_t result = crc16(buffer, BUFFER_SIZE);
        sort(samples, 16);
        for (uint16_t i = 0; i + TAPS <= BUFFER_SIZE; i += TAPS)
            result += (uint32_t)filter(&samples[i]);
        result = m(result, state);
        sink = result;
    }
}
