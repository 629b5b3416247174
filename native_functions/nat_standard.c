// Descriptions of the standard natives: names, documentation strings and
// parameters exactly as upstream sends them (language.md §13.1), so that
// our nodes describe themselves like upstream ones and the compiler numbers
// them the same way.
//
// stack_words = parameters + size-0 parameters + distinct templates
// (bytecode.md §9); the tests check it for every entry.

#include "nat_internal.h"
#include "nat_standard.h"

// Parameter lists, each shared by the natives that have it.
static const vm_native_parameter dest_src[] = { { TEMPLATE_N, "dest" }, { TEMPLATE_N, "src" } };
static const vm_native_parameter dest_value[] = { { TEMPLATE_N, "dest" }, { SCALAR, "value" } };
static const vm_native_parameter dest_src_scalar[] = { { TEMPLATE_N, "dest" },
                                                       { TEMPLATE_N, "src" },
                                                       { SCALAR, "scalar" } };
static const vm_native_parameter dest_src1_src2[] = { { TEMPLATE_N, "dest" },
                                                      { TEMPLATE_N, "src1" },
                                                      { TEMPLATE_N, "src2" } };
static const vm_native_parameter dest_src_low_high[] = { { TEMPLATE_N, "dest" },
                                                         { TEMPLATE_N, "src" },
                                                         { TEMPLATE_N, "low" },
                                                         { TEMPLATE_N, "high" } };
static const vm_native_parameter dot_parameters[] = { { SCALAR, "dest" },
                                                      { TEMPLATE_N, "src1" },
                                                      { TEMPLATE_N, "src2" },
                                                      { SCALAR, "shift" } };
static const vm_native_parameter stat_parameters[] = { { TEMPLATE_N, "src" },
                                                       { SCALAR, "min" },
                                                       { SCALAR, "max" },
                                                       { SCALAR, "mean" } };
static const vm_native_parameter argbounds_parameters[] = { { TEMPLATE_N, "src" },
                                                            { SCALAR, "argmin" },
                                                            { SCALAR, "argmax" } };
static const vm_native_parameter array[] = { { TEMPLATE_N, "array" } };
static const vm_native_parameter dest_a_b_c[] = { { TEMPLATE_N, "dest" },
                                                  { TEMPLATE_N, "a" },
                                                  { TEMPLATE_N, "b" },
                                                  { TEMPLATE_N, "c" } };
static const vm_native_parameter dest_y_x[] = { { TEMPLATE_N, "dest" },
                                                { TEMPLATE_N, "y" },
                                                { TEMPLATE_N, "x" } };
static const vm_native_parameter dest_x[] = { { TEMPLATE_N, "dest" }, { TEMPLATE_N, "x" } };
static const vm_native_parameter rot2_parameters[] = { { 2, "dest" }, { 2, "v" }, { SCALAR, "a" } };
static const vm_native_parameter dest[] = { { TEMPLATE_N, "dest" } };
static const vm_native_parameter deque_size[] = { { TEMPLATE_N, "deque" }, { SCALAR, "size" } };
static const vm_native_parameter deque_dest_index[] = { { TEMPLATE_N, "deque" },
                                                        { TEMPLATE_M, "dest" },
                                                        { SCALAR, "index" } };
static const vm_native_parameter deque_src_index[] = { { TEMPLATE_N, "deque" },
                                                       { TEMPLATE_M, "src" },
                                                       { SCALAR, "index" } };
static const vm_native_parameter deque_index_len[] = { { TEMPLATE_N, "deque" },
                                                       { SCALAR, "index" },
                                                       { SCALAR, "len" } };
static const vm_native_parameter deque_src[] = { { TEMPLATE_N, "deque" }, { TEMPLATE_M, "src" } };
static const vm_native_parameter deque_dest[] = { { TEMPLATE_N, "deque" }, { TEMPLATE_M, "dest" } };

NATIVE(math_copy, "math.copy", "copies src to dest element by element", 3, dest_src);
NATIVE(math_fill, "math.fill", "fills dest with constant value", 3, dest_value);
NATIVE(math_addscalar,
       "math.addscalar",
       "add scalar to each element of src and store result to dest",
       4,
       dest_src_scalar);
NATIVE(math_add,
       "math.add",
       "adds src1 and src2, write to dest, element by element",
       4,
       dest_src1_src2);
NATIVE(math_sub,
       "math.sub",
       "substracts src2 from src1 to dest, element by element",
       4,
       dest_src1_src2);
NATIVE(math_mul,
       "math.mul",
       "multiplies src1 and src2 to dest, element by element",
       4,
       dest_src1_src2);
NATIVE(math_div, "math.div", "divides src1 by src2 to dest, element by element", 4, dest_src1_src2);
NATIVE(math_min,
       "math.min",
       "writes the minimum of src1 and src2 to dest, element by element",
       4,
       dest_src1_src2);
NATIVE(math_max,
       "math.max",
       "writes the maximum of src1 and src2 to dest, element by element",
       4,
       dest_src1_src2);
NATIVE(math_clamp,
       "math.clamp",
       "clamp src to low/high bounds into dest, element by element",
       5,
       dest_src_low_high);
NATIVE(math_dot,
       "math.dot",
       "writes the dot product of src1 and src2 to dest, after a shift",
       5,
       dot_parameters);
NATIVE(math_stat, "math.stat", "performs statistics on src", 5, stat_parameters);
NATIVE(math_argbounds,
       "math.argbounds",
       "get the indices (argmin, argmax) of the limit values of src",
       4,
       argbounds_parameters);
NATIVE(math_sort, "math.sort", "sort array in place", 2, array);
NATIVE(math_muldiv,
       "math.muldiv",
       "performs dest = (a*b)/c in 32 bits element by element",
       5,
       dest_a_b_c);
NATIVE(math_atan2, "math.atan2", "performs dest = atan2(y,x) element by element", 4, dest_y_x);
NATIVE(math_sin, "math.sin", "performs dest = sin(x) element by element", 3, dest_x);
NATIVE(math_cos, "math.cos", "performs dest = cos(x) element by element", 3, dest_x);
NATIVE(math_rot2, "math.rot2", "rotates v of angle a to dest", 3, rot2_parameters);
NATIVE(math_sqrt, "math.sqrt", "performs dest = sqrt(x) element by element", 3, dest_x);
NATIVE(math_rand, "math.rand", "fill array with random values", 2, dest);
NATIVE(deque_size, "deque.size", "report size of dest", 3, deque_size);
NATIVE(deque_get, "deque.get", "fill dest from deque at index", 5, deque_dest_index);
NATIVE(deque_set, "deque.set", "copies src to deque at index", 5, deque_src_index);
NATIVE(deque_insert,
       "deque.insert",
       "shift deque at index by len(src) and insert src",
       5,
       deque_src_index);
NATIVE(deque_erase, "deque.erase", "shift deque at index by len to erase", 4, deque_index_len);
NATIVE(deque_push_front, "deque.push_front", "insert src before the front of deque", 4, deque_src);
NATIVE(deque_push_back, "deque.push_back", "insert src after the back of deque", 4, deque_src);
NATIVE(deque_pop_front,
       "deque.pop_front",
       "fill dest from front of deque then erase elements",
       4,
       deque_dest);
NATIVE(deque_pop_back,
       "deque.pop_back",
       "fill dest from back of deque then erase elements",
       4,
       deque_dest);

static const vm_native *const standard_natives[NAT_STANDARD_COUNT] = { NAT_STANDARD_LIST };

const vm_native_table nat_standard_table = { standard_natives, NAT_STANDARD_COUNT };
