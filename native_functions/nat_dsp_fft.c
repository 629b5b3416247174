// dsp.fft and dsp.mag: a fixed-point radix-2 FFT on a pair of int16 arrays
// and the magnitude of its result.
//
// The FFT is the iterative decimation-in-time algorithm: bit-reversed
// reordering, then log2(N) stages of butterflies. Each butterfly halves its
// outputs, so the transform computes X[k] / N: with inputs whose complex
// magnitude stays below 32768 no butterfly can grow past the int16 range;
// outputs are still saturated, for inputs with both parts near full scale.
// The file's module (nat_dsp.h) is at its end.

#include <stdbool.h>
#include <stddef.h>

#include "nat_dsp_internal.h"
#include "nat_internal.h"
#include "nat_words.h"

#define FFT_MIN_SIZE 8
#define FFT_MAX_SIZE 128

// Q15 fixed point: 1.0 is 2^15.
#define Q15_SHIFT 15

// sin(2 pi k / 128) for k = 0 ... 32 (a quarter wave of the largest FFT), in
// Q15: round(32768 sin(...)) with 1.0 clamped to 32767. Generated with
//   [min(32767, round(32768 * sin(2 * pi * k / 128))) for k in range(33)]
#define SINE_TABLE_QUARTER 32
#define SINE_TABLE_PERIOD  128
static const int16_t quarter_sine_q15[SINE_TABLE_QUARTER + 1] = {
    0,     1608,  3212,  4808,  6393,  7962,  9512,  11039, 12540, 14010, 15447,
    16846, 18205, 19520, 20788, 22006, 23170, 24279, 25330, 26320, 27246, 28106,
    28899, 29622, 30274, 30853, 31357, 31786, 32138, 32413, 32610, 32729, 32767
};

// sin(2 pi k / 128) in Q15 for 0 <= k < 64 (the half period twiddles need).
static int16_t sine_q15(uint16_t k)
{
    return k <= SINE_TABLE_QUARTER ? quarter_sine_q15[k]
                                   : quarter_sine_q15[2 * SINE_TABLE_QUARTER - k];
}

// cos(2 pi k / 128) in Q15 for 0 <= k < 64.
static int16_t cosine_q15(uint16_t k)
{
    return k <= SINE_TABLE_QUARTER ? quarter_sine_q15[SINE_TABLE_QUARTER - k]
                                   : (int16_t)-quarter_sine_q15[k - SINE_TABLE_QUARTER];
}

static bool is_valid_fft_size(uint16_t size)
{
    return size >= FFT_MIN_SIZE && size <= FFT_MAX_SIZE && (size & (size - 1)) == 0;
}

// Reorders both arrays so that element i moves to the bit reversal of i.
static void bit_reverse_order(int16_t *real, int16_t *imag, uint16_t size)
{
    uint16_t reversed = 0;
    for (uint16_t i = 0; i < size; ++i) {
        if (i < reversed) {
            int16_t swap = real[i];
            real[i] = real[reversed];
            real[reversed] = swap;
            swap = imag[i];
            imag[i] = imag[reversed];
            imag[reversed] = swap;
        }
        // Add one to `reversed` from its most significant bit down.
        uint16_t bit = size >> 1;
        while (bit != 0 && (reversed & bit) != 0) {
            reversed ^= bit;
            bit >>= 1;
        }
        reversed |= bit;
    }
}

// (a + t) / 2 rounded half up and saturated: one butterfly output.
static int16_t halve_sum(int32_t a, int32_t t)
{
    return nat_dsp_saturate32(nat_dsp_round_shift32(a + t, 1));
}

NATIVE(dsp_fft,
       3,
       "dsp.fft",
       "in-place FFT" W_OF "real,imag (" W_SIZE " 8..128, power" W_OF
       "2); each stage halves, so" W_THE "result is X/N; rounded half up, saturated",
       P(N, "real") P(N, "imag"));

static void nat_dsp_fft_function(vm_state *vm, const int16_t *arguments)
{
    uint16_t size = nat_size_after(arguments, 2);
    if (!is_valid_fft_size(size)) {
        vm_error_node_specific(vm, "dsp.fft: size must be a power of two from 8 to 128");
        return;
    }
    int16_t *spans[2];
    if (!nat_spans(vm, arguments, 2, size, spans))
        return;
    int16_t *real = spans[0];
    int16_t *imag = spans[1];

    bit_reverse_order(real, imag, size);
    // Stage by stage, butterflies span 2 * half elements; their twiddle
    // W^k = exp(-2 pi i k / (2 half)) is entry k * step of the 128-point table.
    for (uint16_t half = 1; half < size; half <<= 1) {
        uint16_t step = (uint16_t)(SINE_TABLE_PERIOD / 2 / half);
        for (uint16_t k = 0; k < half; ++k) {
            int32_t cosine = cosine_q15((uint16_t)(k * step));
            int32_t sine = sine_q15((uint16_t)(k * step));
            for (uint16_t top = k; top < size; top = (uint16_t)(top + 2 * half)) {
                uint16_t bottom = (uint16_t)(top + half);
                // t = bottom * (cos - i sin), rounded to Q0; |t| < 46342.
                // W^0 = 1 exactly (the table's 32767 is 1 - 2^-15).
                int32_t t_real = real[bottom];
                int32_t t_imag = imag[bottom];
                if (k != 0) {
                    t_real = nat_dsp_round_shift32(
                      (int32_t)real[bottom] * cosine + (int32_t)imag[bottom] * sine, Q15_SHIFT);
                    t_imag = nat_dsp_round_shift32(
                      (int32_t)imag[bottom] * cosine - (int32_t)real[bottom] * sine, Q15_SHIFT);
                }
                int32_t top_real = real[top];
                int32_t top_imag = imag[top];
                real[top] = halve_sum(top_real, t_real);
                imag[top] = halve_sum(top_imag, t_imag);
                real[bottom] = halve_sum(top_real, -t_real);
                imag[bottom] = halve_sum(top_imag, -t_imag);
            }
        }
    }
}

// floor(sqrt(value)), digit by digit in base 4 (no division, no float).
static uint32_t integer_square_root(uint32_t value)
{
    uint32_t root = 0;
    uint32_t bit = (uint32_t)1 << 30;
    while (bit > value)
        bit >>= 2;
    while (bit != 0) {
        if (value >= root + bit) {
            value -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return root;
}

NATIVE(dsp_mag,
       4,
       "dsp.mag",
       W_DEST " = floor(sqrt(real^2 + imag^2))" W_ELEMENT_BY_ELEMENT ", saturated to 32767",
       P(N, W_DEST) P(N, "real") P(N, "imag"));

static void nat_dsp_mag_function(vm_state *vm, const int16_t *arguments)
{
    int16_t *spans[3];
    uint16_t length = nat_size_after(arguments, 3);
    if (!nat_spans(vm, arguments, 3, length, spans))
        return;
    for (uint16_t i = 0; i < length; ++i) {
        int32_t re = spans[1][i];
        int32_t im = spans[2][i];
        // At most 2 * 2^30: fits unsigned 32 bits.
        uint32_t energy = (uint32_t)(re * re) + (uint32_t)(im * im);
        uint32_t magnitude = integer_square_root(energy);
        spans[0][i] = magnitude > INT16_MAX ? INT16_MAX : (int16_t)magnitude;
    }
}

static const vm_native fft_natives[] = {
    NAT_RECORD(dsp_fft),
    NAT_RECORD(dsp_mag),
};

const vm_native_module nat_dsp_fft_module = NAT_MODULE(fft_natives);
