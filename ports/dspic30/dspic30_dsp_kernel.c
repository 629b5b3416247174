// The inner loop of dsp.fir, dsp.corr and dsp.conv on the dsPIC30F's DSP
// engine, the dsPIC port's chip-accelerated kernel: the dsPIC30F build
// compiles this file instead of native_functions/nat_dsp_kernel.c
// (ports/dspic30/module.mk), and both compute the same function, bit for bit
// (README-dsp.md gives the reasoning).
//
// The portable loop multiplies 16 x 16 bits into 32, then adds into 64
// bits: on a 16-bit chip, several instructions per term. Here each term is
// one MAC into the 40-bit accumulator A, which is exact as long as the sum
// stays within 40 bits, guaranteed for up to DSP_EXACT_PRODUCT_COUNT terms;
// longer sums take the portable loop. The rounding and the saturation to
// int16 are then done in the accumulator with shifts and one SAC.
//
// The engine is driven by one inline assembly block, written from the
// 16-bit MCU and DSC Programmer's Reference Manual (MAC, SFTAC, SAC, CLR):
// XC16's DSP builtins (__builtin_mac, __builtin_sftac, ...) were tried
// first, and the compiler built from XC16's GPL sources refuses any
// function where SFTAC follows a MAC ("Argument 0 should be an accumulator
// register") unless the accumulator is a volatile register variable, which
// GCC warns about unconditionally. Facts marked ⚠ were not checked against
// the Family Reference Manual.

#include <stddef.h>

#include "dspic30_registers.h"
#include "native_functions/nat_dsp_internal.h"

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

// SFTAC shifts by -16 ... 16 at once.
#define SFTAC_LARGEST_SHIFT 16u

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
    uint16_t saved_corcon = dspic30_read(DSPIC30_CORCON);
    dspic30_write(DSPIC30_CORCON,
                  (uint16_t)((saved_corcon & ~CORCON_US) | CORCON_IF | CORCON_ACCSAT |
                             CORCON_SATDW | CORCON_SATA));

    // Rounded half up: R = floor((S + 2^(shift-1)) / 2^shift), computed as
    // floor((floor(S / 2^(shift-1)) + 1) / 2) (equal, since floor(x / 2) =
    // floor(floor(x) / 2)). SFTAC by a positive count is an arithmetic right
    // shift, that is a floor also for negative S, of at most 16 bits at a
    // time: shift - 1 <= 30 in two steps.
    uint16_t first_shift = shift > 0 ? (uint16_t)(shift - 1) : 0;
    uint16_t first_step = first_shift > SFTAC_LARGEST_SHIFT ? SFTAC_LARGEST_SHIFT : first_shift;
    uint16_t second_step = (uint16_t)(first_shift - first_step);
    int16_t b_stride = (int16_t)(b_step * (int16_t)sizeof(int16_t)); // |b_step| <= 1
    int16_t result;

    // S = sum of a[i] * b[i * b_step], exact: |S| <= 511 * 2^30 < 2^39, so
    // A never saturates. No X/Y prefetch: the VM's variables may lie
    // anywhere in RAM, while prefetches must read X or Y space. MAC takes
    // its factors in W4...W7.
    //
    // Then, when shift > 0, the two shifts, + 1 in bit 0 (the integer
    // product 1 x 1) and one more shift. Last, R moves to bits 31..16 where
    // SAC reads: if |R| < 2^23 the shift is exact, and SAC (SATDW) stores
    // 0x7FFF when R * 2^16 > 2^31 - 1, that is R > 32767, 0x8000 when
    // R < -32768, else bits 31..16 = R. A larger |R| overflows 40 bits: A
    // saturates (SATA, ACCSAT; ⚠ SFTAC saturates like MAC) keeping the
    // sign, and SAC clamps.
    __asm__ volatile("clr     A\n"
                     "cp0     %[count]\n"
                     "bra     z, 2f\n"
                     "1:\n"
                     "mov     [%[a]++], w4\n"
                     "mov     [%[b]], w5\n"
                     "add     %[b], %[b_stride], %[b]\n"
                     "mac     w4*w5, A\n"
                     "dec     %[count], %[count]\n"
                     "bra     nz, 1b\n"
                     "2:\n"
                     "cp0     %[shift]\n"
                     "bra     z, 3f\n"
                     "sftac   A, %[first_step]\n"
                     "sftac   A, %[second_step]\n"
                     "mov     #1, w4\n"
                     "mov     #1, w5\n"
                     "mac     w4*w5, A\n"
                     "sftac   A, #1\n"
                     "3:\n"
                     "sftac   A, #-16\n"
                     "sac     A, #0, %[result]\n"
                     : [a] "+r"(a), [b] "+r"(b), [count] "+r"(count), [result] "=r"(result)
                     : [b_stride] "r"(b_stride),
                       [shift] "r"(shift),
                       [first_step] "r"(first_step),
                       [second_step] "r"(second_step)
                     : "w4", "w5", "cc", "memory");

    dspic30_write(DSPIC30_CORCON, saved_corcon);
    return result;
}
