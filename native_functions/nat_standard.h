// The 30 standard Aseba native functions (language.md §13), in the order of
// upstream's standard library, plus the integer trigonometry they use.
//
// NAT_STANDARD_NAMES is the module's one table: the natives' declarations,
// their records (NAT_STANDARD_LIST) and their count (NAT_STANDARD_COUNT)
// all come from it, as the VM's come from vm_opcodes.h. A native is its
// line there, and its description (NATIVE, nat_internal.h) with its body in
// nat_math.c, nat_trigonometry.c or nat_deque.c. A target lists them in its
// own native table, after or before its own natives, with
// NAT_STANDARD_LIST; host tools that only need the standard library use
// nat_standard_table.

#ifndef NAT_STANDARD_H
#define NAT_STANDARD_H

#include <stdint.h>

#include "vm.h"

// The standard natives by name, in their standard order (their ids):
// X(math_copy) ... Native NAME is the C function nat_NAME_function and the
// packed description (vm.h, vm_native) nat_NAME_description, side by side
// in the file of its family.
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

// The same followed by a comma, so that lists of records follow one
// another: { NAT_STANDARD_LIST NAT_DSP_LIST }.
#define NAT_LIST_ENTRY(name) NAT_RECORD(name),

// Counts a native of a table: NAT_STANDARD_NAMES(NAT_ONE) is +1 +1 ...
#define NAT_ONE(name) +1

// The standard natives in their standard order, as initialisers of an array
// of vm_native (a target's table may add its own before or after).
#define NAT_STANDARD_LIST NAT_STANDARD_NAMES(NAT_LIST_ENTRY)

// Number of entries of NAT_STANDARD_LIST.
#define NAT_STANDARD_COUNT (0 NAT_STANDARD_NAMES(NAT_ONE))

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
