// Descriptions of the standard natives: names, documentation strings and
// parameters exactly as upstream sends them (language.md §13.1), so that
// our nodes describe themselves like upstream ones and the compiler numbers
// them the same way.
//
// stack_words = parameters + size-0 parameters + distinct templates
// (bytecode.md §9); the tests check it for every entry.

#include "nat_internal.h"
#include "nat_standard.h"

static const vm_native_parameter math_copy_parameters[] = { { TEMPLATE_N, "dest" },
                                                            { TEMPLATE_N, "src" } };
NATIVE(math_copy, "math.copy", "copies src to dest element by element", 3);

static const vm_native_parameter math_fill_parameters[] = { { TEMPLATE_N, "dest" },
                                                            { SCALAR, "value" } };
NATIVE(math_fill, "math.fill", "fills dest with constant value", 3);

static const vm_native_parameter math_addscalar_parameters[] = { { TEMPLATE_N, "dest" },
                                                                 { TEMPLATE_N, "src" },
                                                                 { SCALAR, "scalar" } };
NATIVE(math_addscalar,
       "math.addscalar",
       "add scalar to each element of src and store result to dest",
       4);

static const vm_native_parameter math_add_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_N, "src1" },
                                                           { TEMPLATE_N, "src2" } };
NATIVE(math_add, "math.add", "adds src1 and src2, write to dest, element by element", 4);

static const vm_native_parameter math_sub_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_N, "src1" },
                                                           { TEMPLATE_N, "src2" } };
NATIVE(math_sub, "math.sub", "substracts src2 from src1 to dest, element by element", 4);

static const vm_native_parameter math_mul_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_N, "src1" },
                                                           { TEMPLATE_N, "src2" } };
NATIVE(math_mul, "math.mul", "multiplies src1 and src2 to dest, element by element", 4);

static const vm_native_parameter math_div_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_N, "src1" },
                                                           { TEMPLATE_N, "src2" } };
NATIVE(math_div, "math.div", "divides src1 by src2 to dest, element by element", 4);

static const vm_native_parameter math_min_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_N, "src1" },
                                                           { TEMPLATE_N, "src2" } };
NATIVE(math_min, "math.min", "writes the minimum of src1 and src2 to dest, element by element", 4);

static const vm_native_parameter math_max_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_N, "src1" },
                                                           { TEMPLATE_N, "src2" } };
NATIVE(math_max, "math.max", "writes the maximum of src1 and src2 to dest, element by element", 4);

static const vm_native_parameter math_clamp_parameters[] = { { TEMPLATE_N, "dest" },
                                                             { TEMPLATE_N, "src" },
                                                             { TEMPLATE_N, "low" },
                                                             { TEMPLATE_N, "high" } };
NATIVE(math_clamp, "math.clamp", "clamp src to low/high bounds into dest, element by element", 5);

static const vm_native_parameter math_dot_parameters[] = { { SCALAR, "dest" },
                                                           { TEMPLATE_N, "src1" },
                                                           { TEMPLATE_N, "src2" },
                                                           { SCALAR, "shift" } };
NATIVE(math_dot, "math.dot", "writes the dot product of src1 and src2 to dest, after a shift", 5);

static const vm_native_parameter math_stat_parameters[] = { { TEMPLATE_N, "src" },
                                                            { SCALAR, "min" },
                                                            { SCALAR, "max" },
                                                            { SCALAR, "mean" } };
NATIVE(math_stat, "math.stat", "performs statistics on src", 5);

static const vm_native_parameter math_argbounds_parameters[] = { { TEMPLATE_N, "src" },
                                                                 { SCALAR, "argmin" },
                                                                 { SCALAR, "argmax" } };
NATIVE(math_argbounds,
       "math.argbounds",
       "get the indices (argmin, argmax) of the limit values of src",
       4);

static const vm_native_parameter math_sort_parameters[] = { { TEMPLATE_N, "array" } };
NATIVE(math_sort, "math.sort", "sort array in place", 2);

static const vm_native_parameter math_muldiv_parameters[] = { { TEMPLATE_N, "dest" },
                                                              { TEMPLATE_N, "a" },
                                                              { TEMPLATE_N, "b" },
                                                              { TEMPLATE_N, "c" } };
NATIVE(math_muldiv, "math.muldiv", "performs dest = (a*b)/c in 32 bits element by element", 5);

static const vm_native_parameter math_atan2_parameters[] = { { TEMPLATE_N, "dest" },
                                                             { TEMPLATE_N, "y" },
                                                             { TEMPLATE_N, "x" } };
NATIVE(math_atan2, "math.atan2", "performs dest = atan2(y,x) element by element", 4);

static const vm_native_parameter math_sin_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_N, "x" } };
NATIVE(math_sin, "math.sin", "performs dest = sin(x) element by element", 3);

static const vm_native_parameter math_cos_parameters[] = { { TEMPLATE_N, "dest" },
                                                           { TEMPLATE_N, "x" } };
NATIVE(math_cos, "math.cos", "performs dest = cos(x) element by element", 3);

static const vm_native_parameter math_rot2_parameters[] = { { 2, "dest" },
                                                            { 2, "v" },
                                                            { SCALAR, "a" } };
NATIVE(math_rot2, "math.rot2", "rotates v of angle a to dest", 3);

static const vm_native_parameter math_sqrt_parameters[] = { { TEMPLATE_N, "dest" },
                                                            { TEMPLATE_N, "x" } };
NATIVE(math_sqrt, "math.sqrt", "performs dest = sqrt(x) element by element", 3);

static const vm_native_parameter math_rand_parameters[] = { { TEMPLATE_N, "dest" } };
NATIVE(math_rand, "math.rand", "fill array with random values", 2);

static const vm_native_parameter deque_size_parameters[] = { { TEMPLATE_N, "deque" },
                                                             { SCALAR, "size" } };
NATIVE(deque_size, "deque.size", "report size of dest", 3);

static const vm_native_parameter deque_get_parameters[] = { { TEMPLATE_N, "deque" },
                                                            { TEMPLATE_M, "dest" },
                                                            { SCALAR, "index" } };
NATIVE(deque_get, "deque.get", "fill dest from deque at index", 5);

static const vm_native_parameter deque_set_parameters[] = { { TEMPLATE_N, "deque" },
                                                            { TEMPLATE_M, "src" },
                                                            { SCALAR, "index" } };
NATIVE(deque_set, "deque.set", "copies src to deque at index", 5);

static const vm_native_parameter deque_insert_parameters[] = { { TEMPLATE_N, "deque" },
                                                               { TEMPLATE_M, "src" },
                                                               { SCALAR, "index" } };
NATIVE(deque_insert, "deque.insert", "shift deque at index by len(src) and insert src", 5);

static const vm_native_parameter deque_erase_parameters[] = { { TEMPLATE_N, "deque" },
                                                              { SCALAR, "index" },
                                                              { SCALAR, "len" } };
NATIVE(deque_erase, "deque.erase", "shift deque at index by len to erase", 4);

static const vm_native_parameter deque_push_front_parameters[] = { { TEMPLATE_N, "deque" },
                                                                   { TEMPLATE_M, "src" } };
NATIVE(deque_push_front, "deque.push_front", "insert src before the front of deque", 4);

static const vm_native_parameter deque_push_back_parameters[] = { { TEMPLATE_N, "deque" },
                                                                  { TEMPLATE_M, "src" } };
NATIVE(deque_push_back, "deque.push_back", "insert src after the back of deque", 4);

static const vm_native_parameter deque_pop_front_parameters[] = { { TEMPLATE_N, "deque" },
                                                                  { TEMPLATE_M, "dest" } };
NATIVE(deque_pop_front, "deque.pop_front", "fill dest from front of deque then erase elements", 4);

static const vm_native_parameter deque_pop_back_parameters[] = { { TEMPLATE_N, "deque" },
                                                                 { TEMPLATE_M, "dest" } };
NATIVE(deque_pop_back, "deque.pop_back", "fill dest from back of deque then erase elements", 4);

static const vm_native *const standard_natives[NAT_STANDARD_COUNT] = { NAT_STANDARD_LIST };

const vm_native_table nat_standard_table = { standard_natives, NAT_STANDARD_COUNT };
