// The inner loop of dsp.fir, dsp.corr and dsp.conv on the dsPIC30F's DSP
// engine, the dsPIC port's chip-accelerated kernel: the dsPIC30F build
// compiles this file instead of native_functions/nat_dsp_kernel.c
// (hal/dspic30/module.mk), and both compute the same function, bit for bit
// (README-dsp.md gives the reasoning).
//
// The portable loop multiplies 16 x 16 bits into 32, then adds into 64
// bits: on a 16-bit chip, several instructions per term. Here each term is
// one MAC into the 40-bit accumulator A, which is exact as long as the sum
// stays within 40 bits, guaranteed for up to DSP_EXACT_PRODUCT_COUNT terms;
// longer sums take the portable loop. The rounding and the saturation to
// int16 are then done in the accumulator with shifts and one SAC.
//
// XC16 is not available where this was written: the builtins are used as
// Microchip's XC16 C Compiler User's Guide documents them ("DSP builtins":
// __builtin_clr, __builtin_mac, __builtin_sftac, __builtin_sac); facts
// marked ⚠ come from memory of the dsPIC30F Family Reference Manual and
// were not checked against it. tests/native_functions_dsp/ compiles this
// file on the host against a model of those builtins (defining
// NAT_DSP_SIMULATED_DSP_ENGINE and including the model before this file)
// and compares it with the portable loop.

#include <stddef.h>

#include "nat_dsp_internal.h"

#ifndef NAT_DSP_SIMULATED_DSP_ENGINE
#include "dspic30_registers.h"
// CORCON by its data-space address, as the rest of the port reaches SFRs.
#define CORCON (*(volatile uint16_t *)DSPIC30_CORCON)
// Accumulator A as a C variable, the way the XC16 guide's DSP builtin
// examples declare it (`int` is 16 bits with XC16).
#define DSP_ACCUMULATOR_A(name) volatile register int name asm("A")
#endif

// CORCON bits (positions: hardware fact sheet, CORCON row; meanings ⚠).
#define CORCON_IF     (1u << 0)  // 1: integer multiply, product not shifted left
#define CORCON_ACCSAT (1u << 4)  // 1: saturation at 40 bits (9.31), 0: at 32 (1.31)
#define CORCON_SATDW  (1u << 5)  // 1: SAC clamps to 0x7FFF / 0x8000 what overflows 1.31
#define CORCON_SATA   (1u << 7)  // 1: accumulator A saturates instead of wrapping
#define CORCON_US     (1u << 12) // 0: signed x signed multiply

// Each product is at most 2^30 in magnitude ((-32768)^2 = 2^30), and A holds
// -2^39 ... 2^39 - 1: 511 products always fit (511 * 2^30 < 2^39 - 2^30),
// 512 of (-32768)^2 would not. The e-puck's whole variable memory is 509
// words, so no script reaches the fallback there.
#define DSP_EXACT_PRODUCT_COUNT 511

// A's integer value is in bits 39..0; SAC stores bits 31..16.
#define ACCUMULATOR_HIGH_WORD_SHIFT 16

// The portable loop (nat_dsp_kernel.c), for sums too long for A.
static int16_t long_scaled_dot_product(const int16_t *a,
                                       const int16_t *b,
                                       int16_t b_step,
                                       uint16_t count,
                                       uint16_t shift)
{
    int64_t sum = 0;
    int32_t b_offset = 0;
    for (uint16_t i = 0; i < count; ++i) {
        sum += (int32_t)a[i] * b[b_offset];
        b_offset += b_step;
    }
    return nat_dsp_saturate(nat_dsp_round_shift(sum, shift));
}

int16_t nat_dsp_scaled_dot_product(const int16_t *a,
                                   const int16_t *b,
                                   int16_t b_step,
                                   uint16_t count,
                                   uint16_t shift)
{
    if (count > DSP_EXACT_PRODUCT_COUNT)
        return long_scaled_dot_product(a, b, b_step, count, shift);

    // Integer signed products, A saturating at 40 bits, saturating stores;
    // the other bits (PSV, the interrupt level) are kept, and everything is
    // restored before returning. Writing back the read value leaves the DO
    // loop bits alone: DL is read-only and EDT reads as 0 (⚠).
    uint16_t saved_corcon = CORCON;
    CORCON = (uint16_t)((saved_corcon & ~CORCON_US) | CORCON_IF | CORCON_ACCSAT | CORCON_SATDW |
                        CORCON_SATA);

    // S = sum of a[i] * b[i * b_step], exact: |S| <= 511 * 2^30 < 2^39, so
    // A never saturates. No X/Y prefetch: the VM's variables may lie
    // anywhere in RAM, while prefetches must read X or Y space.
    DSP_ACCUMULATOR_A(accumulator);
    accumulator = __builtin_clr();
    int16_t b_offset = 0; // |b_offset| <= count <= 511
    for (uint16_t i = 0; i < count; ++i) {
        accumulator =
          __builtin_mac(accumulator, a[i], b[b_offset], NULL, NULL, 0, NULL, NULL, 0, NULL, 0);
        b_offset = (int16_t)(b_offset + b_step);
    }

    // Rounded half up: R = floor((S + 2^(shift-1)) / 2^shift), computed as
    // floor((floor(S / 2^(shift-1)) + 1) / 2) (equal, since floor(x / 2) =
    // floor(floor(x) / 2)). SFTAC by a positive count is an arithmetic right
    // shift, that is a floor also for negative S; it takes only literal
    // counts, hence the binary steps for shift - 1 = 0 ... 30.
    if (shift > 0) {
        uint16_t first_shift = (uint16_t)(shift - 1);
        if (first_shift & 16)
            accumulator = __builtin_sftac(accumulator, 16);
        if (first_shift & 8)
            accumulator = __builtin_sftac(accumulator, 8);
        if (first_shift & 4)
            accumulator = __builtin_sftac(accumulator, 4);
        if (first_shift & 2)
            accumulator = __builtin_sftac(accumulator, 2);
        if (first_shift & 1)
            accumulator = __builtin_sftac(accumulator, 1);
        // + 1 in bit 0: the integer product 1 x 1.
        accumulator = __builtin_mac(accumulator, 1, 1, NULL, NULL, 0, NULL, NULL, 0, NULL, 0);
        accumulator = __builtin_sftac(accumulator, 1);
    }

    // Saturated to int16: R moves to bits 31..16, where SAC reads. If
    // |R| < 2^23 the shift is exact, and SAC (SATDW) stores 0x7FFF when
    // R * 2^16 > 2^31 - 1, that is R > 32767, 0x8000 when R < -32768, else
    // bits 31..16 = R. A larger |R| overflows 40 bits: A saturates (SATA,
    // ACCSAT ⚠ SFTAC saturates like MAC) keeping the sign, and SAC clamps.
    accumulator = __builtin_sftac(accumulator, -ACCUMULATOR_HIGH_WORD_SHIFT);
    int16_t result = (int16_t)__builtin_sac(accumulator, 0);

    CORCON = saved_corcon;
    return result;
}
