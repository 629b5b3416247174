// Signal-processing natives for the e-puck's sensors (microphones, camera
// lines, proximity sensors): fixed-point FFT and magnitude, FIR and biquad
// IIR filters, correlation, convolution and peak search.
//
// Portable C99 like the standard natives: no floating point, no allocation,
// all arithmetic in fixed-width integers, every result rounded half up and
// saturated to int16; the formats are in each description string and in
// the comments of nat_dsp.c. A target lists them in its native table with
// NAT_DSP_LIST, normally right after NAT_STANDARD_LIST.

#ifndef NAT_DSP_H
#define NAT_DSP_H

#include "vm.h"

extern const vm_native nat_dsp_fft;
extern const vm_native nat_dsp_mag;
extern const vm_native nat_dsp_fir;
extern const vm_native nat_dsp_iir;
extern const vm_native nat_dsp_corr;
extern const vm_native nat_dsp_conv;
extern const vm_native nat_dsp_peak;

// The DSP natives, as initialisers of an array of `const vm_native *`.
#define NAT_DSP_LIST                                                                               \
    &nat_dsp_fft, &nat_dsp_mag, &nat_dsp_fir, &nat_dsp_iir, &nat_dsp_corr, &nat_dsp_conv,          \
      &nat_dsp_peak

// Number of entries of NAT_DSP_LIST.
#define NAT_DSP_COUNT 7

#endif
