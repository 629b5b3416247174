// The 30 standard Aseba native functions (language.md §13), in the order of
// upstream's standard library, plus the integer trigonometry they use.
//
// Each file of natives owns its module (vm.h, vm_native_module): a native's
// description (NATIVE, nat_internal.h) and body stand side by side in the
// file of its family, and its record in the file's list at the end, whose
// count follows from sizeof. The standard order (the natives' ids) is the
// math module's natives (nat_math.c: math.copy ... math.rand) then the
// deque module's (nat_deque.c). A target lists these modules in its own
// table, after or before its own, with NAT_STANDARD_MODULES; host tools
// that only need the standard library use nat_standard_table.

#ifndef NAT_STANDARD_H
#define NAT_STANDARD_H

#include <stdint.h>

#include "vm.h"

// The math.* natives (nat_math.c) and the deque.* ones (nat_deque.c).
extern const vm_native_module nat_math_module;
extern const vm_native_module nat_deque_module;

// The standard modules in their standard order, as initialisers of an
// array of module pointers: { NAT_STANDARD_MODULES NAT_DSP_MODULES }.
#define NAT_STANDARD_MODULES &nat_math_module, &nat_deque_module,

// A table of exactly the standard natives (the desktop dummy node's list).
extern const vm_native_table nat_standard_table;

// Angles are int16 with 32768 for pi; sines are 1.15 fixed point.
#define NAT_SINE_FRACTION_BITS 15

// sin(angle) in [-32767, 32767], bit-exact with upstream Aseba.
int16_t nat_sin(int16_t angle);

// cos(angle) in [-32767, 32767], bit-exact with upstream Aseba.
int16_t nat_cos(int16_t angle);

// atan2(y, x) as an angle, bit-exact with upstream Aseba.
int16_t nat_atan2(int16_t y, int16_t x);

// floor(sqrt(x)) for x >= 0; 0 for x < 0.
int16_t nat_sqrt(int16_t x);

#endif
