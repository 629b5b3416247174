// dsp.fir and dsp.iir: filters over an int16 signal.
//
// Both sum their products exactly (dsp.fir with nat_dsp_scaled_dot_product,
// the loop the dsPIC runs on its DSP engine), then round half up once and
// saturate to int16: the result is the exact filter output, rounded, for
// any number of taps, and clips instead of wrapping at the extremes.
// The file's module (nat_dsp.h) is at its end.

#include <stddef.h>

#include "nat_dsp_internal.h"
#include "nat_internal.h"
#include "nat_words.h"

// FIR coefficients are Q15 (32767 is 0.99997); IIR coefficients are Q14
// (16384 is 1.0) so that a biquad's a1, up to 2 in magnitude, fits.
#define FIR_COEFFICIENT_SHIFT 15
#define IIR_COEFFICIENT_SHIFT 14

// dsp.iir's fixed sizes and the order of its arrays.
#define IIR_COEFFICIENT_COUNT 5 // b0 b1 b2 a1 a2
#define IIR_STATE_COUNT       4 // x[n-1] x[n-2] y[n-1] y[n-2]
enum { IIR_B0, IIR_B1, IIR_B2, IIR_A1, IIR_A2 };
enum { IIR_X1, IIR_X2, IIR_Y1, IIR_Y2 };

NATIVE(dsp_fir,
       5,
       "dsp.fir",
       "FIR filter: " W_DEST "[n] = sum c[k]*" W_SRC "[n-k] / 32768 (c in Q15, " W_SRC
       " zero before its start), rounded, saturated; " W_DEST " may be " W_SRC,
       P(N, W_DEST) P(N, W_SRC) P(M, "coefficients"));

static void nat_dsp_fir_function(vm_state *vm, const int16_t *arguments)
{
    uint16_t length = nat_size_after(arguments, 3);
    uint16_t tap_count = nat_length(arguments[4]);
    int16_t *signals[2];
    if (!nat_spans(vm, arguments, 2, length, signals))
        return;
    const int16_t *coefficients = vm_variables(vm, (uint16_t)arguments[2], tap_count);
    if (coefficients == NULL)
        return;
    int16_t *dest = signals[0];
    const int16_t *src = signals[1];

    // Samples before src[0] are zero (no history). Computed from the last
    // output down so that dest may be src itself: dest[n] only reads src[0..n],
    // none of which is overwritten yet.
    for (uint16_t n = length; n-- > 0;) {
        uint16_t taps = n < tap_count ? (uint16_t)(n + 1) : tap_count;
        // sum of coefficients[k] * src[n - k]: src read backwards from src[n].
        dest[n] =
          nat_dsp_scaled_dot_product(coefficients, src + n, -1, taps, FIR_COEFFICIENT_SHIFT);
    }
}

NATIVE(dsp_iir,
       5,
       "dsp.iir",
       "biquad: y = (b0 x + b1 x1 + b2 x2 - a1 y1 - a2 y2) / 16384; coefficients [b0 b1 b2 a1 a2] "
       "in Q14, state [x1 x2 y1 y2] kept between calls; rounded, saturated",
       P(N, W_DEST) P(N, W_SRC) P(5, "coefficients") P(4, "state"));

static void nat_dsp_iir_function(vm_state *vm, const int16_t *arguments)
{
    uint16_t length = nat_size_after(arguments, 4);
    int16_t *signals[2];
    if (!nat_spans(vm, arguments, 2, length, signals))
        return;
    const int16_t *coefficient_span =
      vm_variables(vm, (uint16_t)arguments[2], IIR_COEFFICIENT_COUNT);
    if (coefficient_span == NULL)
        return;
    int16_t *state_span = vm_variables(vm, (uint16_t)arguments[3], IIR_STATE_COUNT);
    if (state_span == NULL)
        return;
    int16_t *dest = signals[0];
    const int16_t *src = signals[1];

    // Local copies: dest may overlap them, and the state is written once.
    int32_t b0 = coefficient_span[IIR_B0], b1 = coefficient_span[IIR_B1];
    int32_t b2 = coefficient_span[IIR_B2], a1 = coefficient_span[IIR_A1];
    int32_t a2 = coefficient_span[IIR_A2];
    int16_t x1 = state_span[IIR_X1], x2 = state_span[IIR_X2];
    int16_t y1 = state_span[IIR_Y1], y2 = state_span[IIR_Y2];

    // Direct form I: y = b0 x + b1 x[n-1] + b2 x[n-2] - a1 y[n-1] - a2 y[n-2].
    // Its state is made of saturated inputs and outputs, so it cannot wrap.
    for (uint16_t n = 0; n < length; ++n) {
        int16_t x = src[n];
        int64_t sum = (int64_t)(b0 * x) + (int64_t)(b1 * x1) + (int64_t)(b2 * x2) -
                      (int64_t)(a1 * y1) - (int64_t)(a2 * y2);
        int16_t y = nat_dsp_saturate(nat_dsp_round_shift(sum, IIR_COEFFICIENT_SHIFT));
        dest[n] = y;
        x2 = x1;
        x1 = x;
        y2 = y1;
        y1 = y;
    }
    state_span[IIR_X1] = x1;
    state_span[IIR_X2] = x2;
    state_span[IIR_Y1] = y1;
    state_span[IIR_Y2] = y2;
}

static const vm_native filter_natives[] = {
    NAT_RECORD(dsp_fir),
    NAT_RECORD(dsp_iir),
};

const vm_native_module nat_dsp_filter_module = NAT_MODULE(filter_natives);
