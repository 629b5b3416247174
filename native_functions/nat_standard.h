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

// The standard natives by name, in their standard order: X(math_copy) ...
// Native NAME is the C function nat_NAME_function and the packed
// description (vm.h, vm_native) nat_NAME_description of nat_standard.c.
#define NAT_STANDARD_NAMES(X)                                                                      \
    X(math_copy)                                                                                   \
    X(math_fill)                                                                                   \
    X(math_addscalar)                                                                              \
    X(math_add)                                                                                    \
    X(math_sub)                                                                                    \
    X(math_mul)                                                                                    \
    X(math_div)                                                                                    \
    X(math_min)                                                                                    \
    X(math_max)                                                                                    \
    X(math_clamp)                                                                                  \
    X(math_dot)                                                                                    \
    X(math_stat)                                                                                   \
    X(math_argbounds)                                                                              \
    X(math_sort)                                                                                   \
    X(math_muldiv)                                                                                 \
    X(math_atan2)                                                                                  \
    X(math_sin)                                                                                    \
    X(math_cos)                                                                                    \
    X(math_rot2)                                                                                   \
    X(math_sqrt)                                                                                   \
    X(math_rand)                                                                                   \
    X(deque_size)                                                                                  \
    X(deque_get)                                                                                   \
    X(deque_set)                                                                                   \
    X(deque_insert)                                                                                \
    X(deque_erase)                                                                                 \
    X(deque_push_front)                                                                            \
    X(deque_push_back)                                                                             \
    X(deque_pop_front)                                                                             \
    X(deque_pop_back)

// Declares native NAME's function and description.
#define NAT_DECLARE(name)                                                                          \
    void nat_##name##_function(vm_state *vm, const int16_t *arguments);                            \
    extern const char nat_##name##_description[];
NAT_STANDARD_NAMES(NAT_DECLARE)

// The record (vm_native) of native NAME.
#define NAT_RECORD(name)                                                                           \
    {                                                                                              \
        nat_##name##_function, nat_##name##_description                                            \
    }

// The standard natives in their standard order, as initialisers of an array
// of vm_native (a target's table may add its own before or after).
#define NAT_STANDARD_LIST                                                                          \
    NAT_RECORD(math_copy), NAT_RECORD(math_fill), NAT_RECORD(math_addscalar),                      \
      NAT_RECORD(math_add), NAT_RECORD(math_sub), NAT_RECORD(math_mul), NAT_RECORD(math_div),      \
      NAT_RECORD(math_min), NAT_RECORD(math_max), NAT_RECORD(math_clamp), NAT_RECORD(math_dot),    \
      NAT_RECORD(math_stat), NAT_RECORD(math_argbounds), NAT_RECORD(math_sort),                    \
      NAT_RECORD(math_muldiv), NAT_RECORD(math_atan2), NAT_RECORD(math_sin), NAT_RECORD(math_cos), \
      NAT_RECORD(math_rot2), NAT_RECORD(math_sqrt), NAT_RECORD(math_rand), NAT_RECORD(deque_size), \
      NAT_RECORD(deque_get), NAT_RECORD(deque_set), NAT_RECORD(deque_insert),                      \
      NAT_RECORD(deque_erase), NAT_RECORD(deque_push_front), NAT_RECORD(deque_push_back),          \
      NAT_RECORD(deque_pop_front), NAT_RECORD(deque_pop_back)

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
