// The portable inner loop of dsp.fir, dsp.corr and dsp.conv: a sum of
// products, exact in 64 bits, rounded and saturated once at the end.
//
// Every build but the dsPIC30F one compiles this file; the dsPIC30F build
// compiles ports/dspic30/dspic30_dsp_kernel.c, the same function on the DSP
// engine (ports/dspic30/module.mk makes the swap).

#include "nat_dsp_internal.h"

int16_t nat_dsp_scaled_dot_product(const int16_t *a,
                                   const int16_t *b,
                                   int16_t b_step,
                                   uint16_t count,
                                   uint16_t shift)
{
    // An offset rather than a moving pointer: a pointer stepped past the
    // first element of b (b_step = -1) would be undefined behaviour.
    int64_t sum = 0;
    int32_t b_offset = 0;
    for (uint16_t i = 0; i < count; ++i) {
        sum += (int32_t)a[i] * b[b_offset];
        b_offset += b_step;
    }
    return nat_dsp_saturate(nat_dsp_round_shift(sum, shift));
}
