// What the files of the DSP natives share: the fixed-point functions they all
// round and saturate with. Not for use outside native_functions/.

#ifndef NAT_DSP_INTERNAL_H
#define NAT_DSP_INTERNAL_H

#include <stdint.h>

#include "nat_dsp.h"
#include "vm.h"

// Largest right shift dsp.corr and dsp.conv accept.
#define NAT_DSP_MAX_SHIFT 31

// `value` clamped to the int16 range.
static inline int16_t nat_dsp_saturate(int64_t value)
{
    if (value > INT16_MAX)
        return INT16_MAX;
    if (value < INT16_MIN)
        return INT16_MIN;
    return (int16_t)value;
}

// value / 2^shift rounded half up (towards +infinity on ties), for
// 0 <= shift <= 62. Relies on >> of a negative number being arithmetic, as
// on every compiler the project builds with (gcc, XC16).
static inline int64_t nat_dsp_round_shift(int64_t value, uint16_t shift)
{
    if (shift == 0)
        return value;
    return (value + ((int64_t)1 << (shift - 1))) >> shift;
}

// The same for 32-bit values (0 <= shift <= 30), cheaper on 16-bit chips;
// the caller guarantees that value + 2^(shift-1) does not overflow.
static inline int32_t nat_dsp_round_shift32(int32_t value, uint16_t shift)
{
    if (shift == 0)
        return value;
    return (value + ((int32_t)1 << (shift - 1))) >> shift;
}

// `value` clamped to the int16 range, for 32-bit values.
static inline int16_t nat_dsp_saturate32(int32_t value)
{
    if (value > INT16_MAX)
        return INT16_MAX;
    if (value < INT16_MIN)
        return INT16_MIN;
    return (int16_t)value;
}

// The inner loop of dsp.fir, dsp.corr and dsp.conv:
//   sum of a[i] * b[i * b_step] for i = 0 ... count - 1, b_step = 1 or -1,
// exact, then divided by 2^shift rounded half up (nat_dsp_round_shift,
// 0 <= shift <= NAT_DSP_MAX_SHIFT) and saturated to int16. Returns 0 when
// count is 0. nat_dsp_kernel.c is the portable version; the dsPIC30F build
// compiles ports/dspic30/dspic30_dsp_kernel.c, its DSP-engine version, instead.
int16_t nat_dsp_scaled_dot_product(const int16_t *a,
                                   const int16_t *b,
                                   int16_t b_step,
                                   uint16_t count,
                                   uint16_t shift);

#endif
