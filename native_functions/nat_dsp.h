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

#include "nat_standard.h"
#include "vm.h"

// The DSP natives by name, in their order: native NAME is nat_NAME_function
// and nat_NAME_description (nat_dsp.c), as for the standard natives.
#define NAT_DSP_NAMES(X)                                                                           \
    X(dsp_fft) X(dsp_mag) X(dsp_fir) X(dsp_iir) X(dsp_corr) X(dsp_conv) X(dsp_peak)
NAT_DSP_NAMES(NAT_DECLARE)

// The DSP natives, as initialisers of an array of vm_native.
#define NAT_DSP_LIST                                                                               \
    NAT_RECORD(dsp_fft), NAT_RECORD(dsp_mag), NAT_RECORD(dsp_fir), NAT_RECORD(dsp_iir),            \
      NAT_RECORD(dsp_corr), NAT_RECORD(dsp_conv), NAT_RECORD(dsp_peak)

// Number of entries of NAT_DSP_LIST.
#define NAT_DSP_COUNT 7

#endif
