// A C model of the parts of the dsPIC30F DSP engine that
// hal/dspic30/dspic30_dsp_kernel.c uses, so that the file compiles and runs
// on the host (tests/native_functions_dsp/module.mk builds it with
// NAT_DSP_SIMULATED_DSP_ENGINE and includes this model ahead of it).
//
// What is modelled, as the dsPIC30F Family Reference Manual describes the
// engine (⚠ from memory, not re-read):
// - accumulator A: a 40-bit two's complement number;
// - MAC in integer mode (CORCON.IF = 1), signed operands (CORCON.US = 0):
//   A + a * b, the 32-bit product not shifted;
// - every write to A: with CORCON.SATA = 0 it wraps modulo 2^40; with
//   SATA = 1 it saturates, at 40 bits (-2^39 ... 2^39 - 1) if CORCON.ACCSAT
//   = 1, at 32 bits (-2^31 ... 2^31 - 1) if ACCSAT = 0;
// - SFTAC: shift right (count > 0, arithmetic) or left (count < 0), -16...16;
// - SAC with shift -8...7: bits 31..16 of A shifted, truncated; with
//   CORCON.SATDW = 1, 0x7FFF or 0x8000 instead when the shifted value is
//   outside -2^31 ... 2^31 - 1.
// Fractional mode, unsigned multiplies and X/Y prefetches are not
// modelled: the model stops the test if the code asks for them.

#ifndef DSPIC30_DSP_ENGINE_MODEL_H
#define DSPIC30_DSP_ENGINE_MODEL_H

#include <assert.h>
#include <stddef.h>
#include <stdint.h>

// CORCON, which the test sets and reads back (extern "C" there).
extern uint16_t dspic30_model_corcon;
#define CORCON dspic30_model_corcon

#define MODEL_CORCON_IF     (1u << 0)
#define MODEL_CORCON_ACCSAT (1u << 4)
#define MODEL_CORCON_SATDW  (1u << 5)
#define MODEL_CORCON_SATA   (1u << 7)
#define MODEL_CORCON_US     (1u << 12)

#define MODEL_ACCUMULATOR_BITS 40
#define MODEL_WORD_BITS        16

// Accumulator A's value. The C variable that names A in XC16 is a plain
// token here: only A exists in the model.
static int64_t model_accumulator_a;
#define DSP_ACCUMULATOR_A(name) int name = 0

// `value` stored into a 40-bit accumulator under the current CORCON.
static int64_t model_store(int64_t value)
{
    const int64_t max40 = ((int64_t)1 << (MODEL_ACCUMULATOR_BITS - 1)) - 1;
    const int64_t min40 = -max40 - 1;
    if (dspic30_model_corcon & MODEL_CORCON_SATA) {
        int64_t max = (dspic30_model_corcon & MODEL_CORCON_ACCSAT) ? max40 : INT32_MAX;
        int64_t min = (dspic30_model_corcon & MODEL_CORCON_ACCSAT) ? min40 : INT32_MIN;
        return value > max ? max : value < min ? min : value;
    }
    // Wraps: keep the low 40 bits, sign-extended.
    uint64_t low_bits = (uint64_t)value & (((uint64_t)1 << MODEL_ACCUMULATOR_BITS) - 1);
    return low_bits > (uint64_t)max40 ? (int64_t)low_bits - ((int64_t)1 << MODEL_ACCUMULATOR_BITS)
                                      : (int64_t)low_bits;
}

static int model_clr(void)
{
    model_accumulator_a = 0;
    return 0;
}

static int model_mac(int accumulator,
                     int a,
                     int b,
                     const void *x_prefetch,
                     const void *y_prefetch,
                     const void *write_back)
{
    (void)accumulator;
    assert(x_prefetch == NULL && y_prefetch == NULL && write_back == NULL);
    assert((dspic30_model_corcon & MODEL_CORCON_IF) != 0); // integer mode only
    assert((dspic30_model_corcon & MODEL_CORCON_US) == 0); // signed only
    assert(a >= INT16_MIN && a <= INT16_MAX && b >= INT16_MIN && b <= INT16_MAX);
    model_accumulator_a = model_store(model_accumulator_a + (int64_t)a * b);
    return 0;
}

static int model_sftac(int accumulator, int count)
{
    (void)accumulator;
    assert(count >= -16 && count <= 16);
    if (count >= 0)
        model_accumulator_a = model_accumulator_a >> count; // arithmetic on gcc
    else
        model_accumulator_a = model_store(model_accumulator_a * ((int64_t)1 << -count));
    return 0;
}

static int16_t model_sac(int accumulator, int count)
{
    (void)accumulator;
    assert(count >= -8 && count <= 7);
    int64_t shifted =
      count >= 0 ? model_accumulator_a >> count : model_accumulator_a * ((int64_t)1 << -count);
    if (dspic30_model_corcon & MODEL_CORCON_SATDW) {
        if (shifted > INT32_MAX)
            return INT16_MAX;
        if (shifted < INT32_MIN)
            return INT16_MIN;
    }
    return (int16_t)(uint16_t)((uint64_t)shifted >> MODEL_WORD_BITS);
}

// XC16's builtins, by their documented prototypes.
#define __builtin_clr() model_clr()
#define __builtin_mac(accumulator, a, b, xptr, xval, xincr, yptr, yval, yincr, awb, awb_accum)     \
    model_mac(accumulator, a, b, xptr, yptr, awb)
#define __builtin_sftac(accumulator, count) model_sftac(accumulator, count)
#define __builtin_sac(accumulator, count)   model_sac(accumulator, count)

#endif
