// dsp.corr, dsp.conv and dsp.peak: sums of lagged products of two signals
// and the search for their maximum (the delay between two microphones is
// the lag at which their correlation peaks).
//
// Sums are exact (nat_dsp_scaled_dot_product: 64 bits, or the dsPIC's DSP
// engine), shifted right by the script's `shift` (rounded half up) and
// saturated to int16. dest must not overlap a or b: the sums
// read them after dest is partly written (memory stays safe either way).
// The file's module (nat_dsp.h) is at its end.

#include <stddef.h>

#include "nat_dsp_internal.h"
#include "nat_internal.h"
#include "nat_words.h"

// Argument layout of dsp.corr and dsp.conv: &dest, &a, &b, &shift, then the
// sizes of templates -1 (dest), -2 (a) and -3 (b).
enum { ARG_DEST, ARG_A, ARG_B, ARG_SHIFT, ARG_DEST_SIZE, ARG_A_SIZE, ARG_B_SIZE };

typedef struct lagged_signals {
    int16_t *dest;
    const int16_t *a;
    const int16_t *b;
    uint16_t dest_size;
    uint16_t a_size;
    uint16_t b_size;
    uint16_t shift;
} lagged_signals;

// Fetches the arguments of dsp.corr or dsp.conv; false when the VM stopped.
static bool fetch_lagged_signals(vm_state *vm, const int16_t *arguments, lagged_signals *signals)
{
    signals->dest_size = nat_length(arguments[ARG_DEST_SIZE]);
    signals->a_size = nat_length(arguments[ARG_A_SIZE]);
    signals->b_size = nat_length(arguments[ARG_B_SIZE]);
    signals->dest = vm_variables(vm, (uint16_t)arguments[ARG_DEST], signals->dest_size);
    if (signals->dest == NULL)
        return false;
    signals->a = vm_variables(vm, (uint16_t)arguments[ARG_A], signals->a_size);
    if (signals->a == NULL)
        return false;
    signals->b = vm_variables(vm, (uint16_t)arguments[ARG_B], signals->b_size);
    if (signals->b == NULL)
        return false;
    const int16_t *shift = vm_variables(vm, (uint16_t)arguments[ARG_SHIFT], 1);
    if (shift == NULL)
        return false;
    if (*shift < 0 || *shift > NAT_DSP_MAX_SHIFT) {
        vm_error_node_specific(vm, "dsp: shift must be from 0 to 31");
        return false;
    }
    signals->shift = (uint16_t)*shift;
    return true;
}

// dest[i] = sum over n of a[n + lag] * b[n], lag = i - dest_size / 2 (integer
// division): lag 0 in the middle, so a dest of 2N-1 holds lags -(N-1)...N-1.
// Terms outside either array are zero. A peak at lag L > 0 means that a
// follows b by L samples (a[n + L] looks like b[n]).
NATIVE(dsp_corr,
       7,
       "dsp.corr",
       "correlation: " W_DEST "[i] = sum a[n+lag]*b[n] >> " W_SHIFT " (0..31), lag = i - " W_SIZE
       "(" W_DEST ")/2; rounded, saturated",
       P(N, W_DEST) P(M, "a") P(P, "b") P(1, W_SHIFT));

static void nat_dsp_corr_function(vm_state *vm, const int16_t *arguments)
{
    lagged_signals s;
    if (!fetch_lagged_signals(vm, arguments, &s))
        return;
    for (uint16_t i = 0; i < s.dest_size; ++i) {
        int32_t lag = (int32_t)i - s.dest_size / 2;
        // n runs over max(0, -lag) ... min(b_size, a_size - lag) - 1.
        int32_t first = lag < 0 ? -lag : 0;
        int32_t end = (int32_t)s.a_size - lag < s.b_size ? (int32_t)s.a_size - lag : s.b_size;
        uint16_t count = end > first ? (uint16_t)(end - first) : 0;
        // No pointer is formed outside the arrays when no term overlaps.
        s.dest[i] =
          count > 0 ? nat_dsp_scaled_dot_product(s.a + first + lag, s.b + first, 1, count, s.shift)
                    : 0;
    }
}

// dest[i] = sum over k of a[k] * b[i - k]: the full convolution has
// a_size + b_size - 1 terms; a shorter dest gets its first ones, a longer
// one zeros after them.
NATIVE(dsp_conv,
       7,
       "dsp.conv",
       "convolution: " W_DEST "[i] = sum a[k]*b[i-k] >> " W_SHIFT " (0..31); full length is " W_SIZE
       "(a)+" W_SIZE "(b)-1; rounded, saturated",
       P(N, W_DEST) P(M, "a") P(P, "b") P(1, W_SHIFT));

static void nat_dsp_conv_function(vm_state *vm, const int16_t *arguments)
{
    lagged_signals s;
    if (!fetch_lagged_signals(vm, arguments, &s))
        return;
    for (uint16_t i = 0; i < s.dest_size; ++i) {
        // k runs over max(0, i - b_size + 1) ... min(i, a_size - 1).
        int32_t first = (int32_t)i - s.b_size + 1 > 0 ? (int32_t)i - s.b_size + 1 : 0;
        int32_t last = (int32_t)i < (int32_t)s.a_size - 1 ? (int32_t)i : (int32_t)s.a_size - 1;
        // b is read backwards from b[i - first].
        uint16_t count = last >= first ? (uint16_t)(last - first + 1) : 0;
        s.dest[i] =
          count > 0 ? nat_dsp_scaled_dot_product(s.a + first, s.b + (i - first), -1, count, s.shift)
                    : 0;
    }
}

NATIVE(dsp_peak,
       4,
       "dsp.peak",
       W_INDEX W_AND W_VALUE W_OF "the first maximum" W_OF W_SRC,
       P(1, W_INDEX) P(1, W_VALUE) P(N, W_SRC));

static void nat_dsp_peak_function(vm_state *vm, const int16_t *arguments)
{
    int16_t *outputs[2];
    if (!nat_spans(vm, arguments, 2, 1, outputs))
        return;
    uint16_t length = nat_size_after(arguments, 3);
    const int16_t *src = vm_variables(vm, (uint16_t)arguments[2], length);
    if (src == NULL || length == 0)
        return;
    // The whole search runs before writing: the outputs may be inside src.
    uint16_t best_index = 0;
    int16_t best_value = src[0];
    for (uint16_t i = 1; i < length; ++i) {
        if (src[i] > best_value) {
            best_value = src[i];
            best_index = i;
        }
    }
    *outputs[0] = (int16_t)best_index;
    *outputs[1] = best_value;
}

static const vm_native correlation_natives[] = {
    NAT_RECORD(dsp_corr),
    NAT_RECORD(dsp_conv),
    NAT_RECORD(dsp_peak),
};

const vm_native_module nat_dsp_correlation_module = NAT_MODULE(correlation_natives);
