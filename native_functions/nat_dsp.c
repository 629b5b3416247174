// Descriptions of the DSP natives: what Aseba Studio and our console show.
// Formats, in the description strings too:
//   dsp.fft   in place, real/imag int16, size 8...128 power of two; each of
//             the log2(N) stages halves (round half up): output X[k] / N.
//             Twiddles Q15. Outputs saturate (only if |input| > 32767).
//   dsp.mag   floor(sqrt(re^2 + im^2)) saturated to 32767.
//   dsp.fir   Q15 taps, dest[n] = sum c[k] src[n-k], src before 0 is 0.
//   dsp.iir   one biquad, Q14 b0 b1 b2 a1 a2, y = b.x - a.y, state
//             [x1 x2 y1 y2] kept by the script between calls.
//   dsp.corr  dest[i] = sum a[n+lag] b[n], lag = i - len(dest)/2, >> shift.
//   dsp.conv  dest[i] = sum a[k] b[i-k], >> shift.
//   dsp.peak  index and value of the first maximum.
// Every result is rounded half up and saturated to int16. The descriptions
// are packed with the standard natives' words (nat_words.h).

#include "nat_dsp.h"
#include "nat_dsp_internal.h"
#include "nat_internal.h"
#include "nat_words.h"

NATIVE(dsp_fft,
       3,
       "dsp.fft",
       "in-place FFT" W_OF "real,imag (" W_SIZE " 8..128, power" W_OF
       "2); each stage halves, so" W_THE "result is X/N; rounded half up, saturated",
       P(N, "real") P(N, "imag"));
NATIVE(dsp_mag,
       4,
       "dsp.mag",
       W_DEST " = floor(sqrt(real^2 + imag^2))" W_ELEMENT_BY_ELEMENT ", saturated to 32767",
       P(N, W_DEST) P(N, "real") P(N, "imag"));
NATIVE(dsp_fir,
       5,
       "dsp.fir",
       "FIR filter: " W_DEST "[n] = sum c[k]*" W_SRC "[n-k] / 32768 (c in Q15, " W_SRC
       " zero before its start), rounded, saturated; " W_DEST " may be " W_SRC,
       P(N, W_DEST) P(N, W_SRC) P(M, "coefficients"));
NATIVE(dsp_iir,
       5,
       "dsp.iir",
       "biquad: y = (b0 x + b1 x1 + b2 x2 - a1 y1 - a2 y2) / 16384; coefficients [b0 b1 b2 a1 a2] "
       "in Q14, state [x1 x2 y1 y2] kept between calls; rounded, saturated",
       P(N, W_DEST) P(N, W_SRC) P(5, "coefficients") P(4, "state"));
NATIVE(dsp_corr,
       7,
       "dsp.corr",
       "correlation: " W_DEST "[i] = sum a[n+lag]*b[n] >> " W_SHIFT " (0..31), lag = i - " W_SIZE
       "(" W_DEST ")/2; rounded, saturated",
       P(N, W_DEST) P(M, "a") P(P, "b") P(1, W_SHIFT));
NATIVE(dsp_conv,
       7,
       "dsp.conv",
       "convolution: " W_DEST "[i] = sum a[k]*b[i-k] >> " W_SHIFT " (0..31); full length is " W_SIZE
       "(a)+" W_SIZE "(b)-1; rounded, saturated",
       P(N, W_DEST) P(M, "a") P(P, "b") P(1, W_SHIFT));
NATIVE(dsp_peak,
       4,
       "dsp.peak",
       W_INDEX W_AND W_VALUE W_OF "the first maximum" W_OF W_SRC,
       P(1, W_INDEX) P(1, W_VALUE) P(N, W_SRC));
