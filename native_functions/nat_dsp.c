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
// Every result is rounded half up and saturated to int16.
//
// stack_words = parameters + size-0 parameters + distinct templates
// (bytecode.md §9); the tests check it for every entry.

#include "nat_dsp.h"
#include "nat_dsp_internal.h"
#include "nat_internal.h"

// Parameter sizes beyond nat_internal.h's.
#define TEMPLATE_P  -3
#define BIQUAD_SIZE 5
#define STATE_SIZE  4

static const vm_native_parameter dsp_fft_parameters[] = { { TEMPLATE_N, "real" },
                                                          { TEMPLATE_N, "imag" } };
NATIVE(dsp_fft,
       "dsp.fft",
       "in-place FFT of real,imag (size 8..128, power of 2); each stage halves, so the result is "
       "X/N; rounded half up, saturated",
       3,
       dsp_fft_parameters);

static const vm_native_parameter dsp_mag_parameters[] = { { TEMPLATE_N, "dest" },
                                                          { TEMPLATE_N, "real" },
                                                          { TEMPLATE_N, "imag" } };
NATIVE(dsp_mag,
       "dsp.mag",
       "dest = floor(sqrt(real^2 + imag^2)) element by element, saturated to 32767",
       4,
       dsp_mag_parameters);

static const vm_native_parameter dsp_fir_parameters[] = { { TEMPLATE_N, "dest" },
                                                          { TEMPLATE_N, "src" },
                                                          { TEMPLATE_M, "coefficients" } };
NATIVE(dsp_fir,
       "dsp.fir",
       "FIR filter: dest[n] = sum c[k]*src[n-k] / 32768 (c in Q15, src zero before its start), "
       "rounded, saturated; dest may be src",
       5,
       dsp_fir_parameters);

static const vm_native_parameter dsp_iir_parameters[] = { { TEMPLATE_N, "dest" },
                                                          { TEMPLATE_N, "src" },
                                                          { BIQUAD_SIZE, "coefficients" },
                                                          { STATE_SIZE, "state" } };
NATIVE(dsp_iir,
       "dsp.iir",
       "biquad: y = (b0 x + b1 x1 + b2 x2 - a1 y1 - a2 y2) / 16384; coefficients [b0 b1 b2 a1 a2] "
       "in Q14, state [x1 x2 y1 y2] kept between calls; rounded, saturated",
       5,
       dsp_iir_parameters);

static const vm_native_parameter dsp_corr_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_M, "a" },
                                                           { TEMPLATE_P, "b" },
                                                           { SCALAR, "shift" } };
NATIVE(dsp_corr,
       "dsp.corr",
       "correlation: dest[i] = sum a[n+lag]*b[n] >> shift (0..31), lag = i - size(dest)/2; "
       "rounded, saturated",
       7,
       dsp_corr_parameters);

static const vm_native_parameter dsp_conv_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_M, "a" },
                                                           { TEMPLATE_P, "b" },
                                                           { SCALAR, "shift" } };
NATIVE(dsp_conv,
       "dsp.conv",
       "convolution: dest[i] = sum a[k]*b[i-k] >> shift (0..31); full length is "
       "size(a)+size(b)-1; rounded, saturated",
       7,
       dsp_conv_parameters);

static const vm_native_parameter dsp_peak_parameters[] = { { SCALAR, "index" },
                                                           { SCALAR, "value" },
                                                           { TEMPLATE_N, "src" } };
NATIVE(dsp_peak, "dsp.peak", "index and value of the first maximum of src", 4, dsp_peak_parameters);
