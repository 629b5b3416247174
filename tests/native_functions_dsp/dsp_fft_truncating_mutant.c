// A deliberate fault, for dsp_fft_exact_test.cpp to prove that it catches
// it: native_functions/nat_dsp_fft.c compiled with its butterfly's halving
// truncated (rounded down) instead of rounded half up, as documented. Only
// the halving (a shift by 1) changes; the twiddle products (a shift by 15)
// keep their rounding. Its natives are static; its module is renamed so
// that it links beside the real one.
//
// If nat_dsp_fft.c stops halving through nat_dsp_round_shift32(..., 1), this
// file compiles the unchanged transform and the test that expects the fault
// to be caught fails: the mutant must then be rewritten, not dropped.

#include "nat_dsp_internal.h"

#define nat_dsp_round_shift32(value, shift)                                                        \
    ((shift) == 1 ? (value) >> 1 : nat_dsp_round_shift32(value, shift))
#define nat_dsp_fft_module nat_dsp_fft_truncating_mutant_module

#include "native_functions/nat_dsp_fft.c"
