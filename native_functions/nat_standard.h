// The 30 standard Aseba native functions (language.md §13), in the order of
// upstream's standard library, plus the integer trigonometry they use.
//
// A target lists them in its own native table, after or before its own
// natives, with NAT_STANDARD_LIST; host tools that only need the standard
// library use nat_standard_table.

#ifndef NAT_STANDARD_H
#define NAT_STANDARD_H

#include <stdint.h>

#include "vm.h"

extern const vm_native nat_math_copy;
extern const vm_native nat_math_fill;
extern const vm_native nat_math_addscalar;
extern const vm_native nat_math_add;
extern const vm_native nat_math_sub;
extern const vm_native nat_math_mul;
extern const vm_native nat_math_div;
extern const vm_native nat_math_min;
extern const vm_native nat_math_max;
extern const vm_native nat_math_clamp;
extern const vm_native nat_math_dot;
extern const vm_native nat_math_stat;
extern const vm_native nat_math_argbounds;
extern const vm_native nat_math_sort;
extern const vm_native nat_math_muldiv;
extern const vm_native nat_math_atan2;
extern const vm_native nat_math_sin;
extern const vm_native nat_math_cos;
extern const vm_native nat_math_rot2;
extern const vm_native nat_math_sqrt;
extern const vm_native nat_math_rand;
extern const vm_native nat_deque_size;
extern const vm_native nat_deque_get;
extern const vm_native nat_deque_set;
extern const vm_native nat_deque_insert;
extern const vm_native nat_deque_erase;
extern const vm_native nat_deque_push_front;
extern const vm_native nat_deque_push_back;
extern const vm_native nat_deque_pop_front;
extern const vm_native nat_deque_pop_back;

// The standard natives in their standard order, as initialisers of an array
// of `const vm_native *` (a target's table may add its own before or after).
#define NAT_STANDARD_LIST                                                                          \
    &nat_math_copy, &nat_math_fill, &nat_math_addscalar, &nat_math_add, &nat_math_sub,             \
      &nat_math_mul, &nat_math_div, &nat_math_min, &nat_math_max, &nat_math_clamp, &nat_math_dot,  \
      &nat_math_stat, &nat_math_argbounds, &nat_math_sort, &nat_math_muldiv, &nat_math_atan2,      \
      &nat_math_sin, &nat_math_cos, &nat_math_rot2, &nat_math_sqrt, &nat_math_rand,                \
      &nat_deque_size, &nat_deque_get, &nat_deque_set, &nat_deque_insert, &nat_deque_erase,        \
      &nat_deque_push_front, &nat_deque_push_back, &nat_deque_pop_front, &nat_deque_pop_back

// Number of entries of NAT_STANDARD_LIST.
#define NAT_STANDARD_COUNT 30

// A table of exactly the standard natives (the desktop dummy node's list).
extern const vm_native_table nat_standard_table;

// Angles are int16 with 32768 for pi; sines are 1.15 fixed point.

// sin(angle) in [-32767, 32767], bit-exact with upstream Aseba.
int16_t nat_sin(int16_t angle);

// cos(angle) in [-32767, 32767], bit-exact with upstream Aseba.
int16_t nat_cos(int16_t angle);

// atan2(y, x) as an angle, bit-exact with upstream Aseba.
int16_t nat_atan2(int16_t y, int16_t x);

// floor(sqrt(x)) for x >= 0; 0 for x < 0.
int16_t nat_sqrt(int16_t x);

#endif
