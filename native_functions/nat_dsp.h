// Signal-processing natives for the e-puck's sensors (microphones, camera
// lines, proximity sensors): fixed-point FFT and magnitude, FIR and biquad
// IIR filters, correlation, convolution and peak search.
//
// Portable C99 like the standard natives: no floating point, no allocation,
// all arithmetic in fixed-width integers, every result rounded half up and
// saturated to int16. A target lists them in its native table with
// NAT_DSP_MODULES, normally right after NAT_STANDARD_MODULES. As for the
// standard natives, each file owns its module: each native's description
// is beside its body, its record in the file's list at the end
// (nat_dsp_fft.c, nat_dsp_filter.c, nat_dsp_correlation.c, in this
// order), with its format, which the description strings say too:
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

#ifndef NAT_DSP_H
#define NAT_DSP_H

#include "nat_standard.h"
#include "vm.h"

// The DSP natives' modules: dsp.fft and dsp.mag; dsp.fir and dsp.iir;
// dsp.corr, dsp.conv and dsp.peak.
extern const vm_native_module nat_dsp_fft_module;
extern const vm_native_module nat_dsp_filter_module;
extern const vm_native_module nat_dsp_correlation_module;

// The DSP modules in their order, as initialisers of an array of module
// pointers.
#define NAT_DSP_MODULES &nat_dsp_fft_module, &nat_dsp_filter_module, &nat_dsp_correlation_module,

#endif
