// The math.* natives of the standard library (language.md §13.2, §13.3):
// element-wise vector operations, statistics, sorting, the trigonometry and
// square root of nat_trigonometry.c, and math.rand; and their module, in
// their standard order (their ids), at the end.
//
// Arguments may overlap (the same variable passed twice, or slices of one
// array): every loop reads the source elements of index i just before it
// writes dest[i], in increasing i, exactly like upstream, so overlapping
// calls give upstream's results.

#include <stddef.h>

#include "nat_internal.h"
#include "nat_words.h"

// The linear congruential generator of math.rand (upstream's constants).
#define RAND_MULTIPLIER 25173u
#define RAND_INCREMENT  13849u

// Shifts of math.dot at and beyond the width of the 32-bit accumulator.
#define DOT_ACCUMULATOR_BITS 32

static int16_t add(int16_t left, int16_t right)
{
    return nat_wrap((int32_t)left + right);
}

static int16_t subtract(int16_t left, int16_t right)
{
    return nat_wrap((int32_t)left - right);
}

static int16_t multiply(int16_t left, int16_t right)
{
    return nat_wrap((int32_t)left * right);
}

static int16_t minimum(int16_t left, int16_t right)
{
    return left < right ? left : right;
}

static int16_t maximum(int16_t left, int16_t right)
{
    return left > right ? left : right;
}

// math.copy is the identity, element by element.
static int16_t identity(int16_t value, int16_t same)
{
    (void)same;
    return value;
}

NATIVE(math_copy,
       3,
       W_MATH "copy",
       "copies " W_SRC W_TO W_DEST W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC));

static void nat_math_copy_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise(vm, arguments, 1, identity);
}

NATIVE(math_fill,
       3,
       W_MATH W_FILL,
       W_FILL "s " W_DEST " with constant " W_VALUE,
       P(N, W_DEST) P(1, W_VALUE));

static void nat_math_fill_function(vm_state *vm, const int16_t *arguments)
{
    uint16_t length = nat_size_after(arguments, 2);
    int16_t *dest = vm_variables(vm, (uint16_t)arguments[0], length);
    if (dest == NULL)
        return;
    const int16_t *value = vm_variables(vm, (uint16_t)arguments[1], 1);
    if (value == NULL)
        return;
    // value is re-read at each element: it may be one of them.
    for (uint16_t i = 0; i < length; ++i)
        dest[i] = *value;
}

NATIVE(math_addscalar,
       4,
       W_MATH W_ADD W_SCALAR,
       W_ADD " " W_SCALAR W_TO "each" W_ELEMENT W_OF W_SRC W_AND "store result" W_TO W_DEST,
       P(N, W_DEST) P(N, W_SRC) P(1, W_SCALAR));

static void nat_math_addscalar_function(vm_state *vm, const int16_t *arguments)
{
    int16_t *spans[2];
    uint16_t length = nat_size_after(arguments, 3);
    if (!nat_spans(vm, arguments, 2, length, spans))
        return;
    const int16_t *scalar = vm_variables(vm, (uint16_t)arguments[2], 1);
    if (scalar == NULL)
        return;
    // Read once, unlike math.fill's value: upstream's order.
    int16_t addend = *scalar;
    for (uint16_t i = 0; i < length; ++i)
        spans[0][i] = add(spans[1][i], addend);
}

NATIVE(math_add,
       4,
       W_MATH W_ADD,
       W_ADD "s " W_SRC1 W_AND W_SRC2 ", " W_WRITE W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));

static void nat_math_add_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise(vm, arguments, 2, add);
}

NATIVE(math_sub,
       4,
       W_MATH "sub",
       "substracts " W_SRC2 W_FROM W_SRC1 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));

static void nat_math_sub_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise(vm, arguments, 2, subtract);
}

NATIVE(math_mul,
       4,
       W_MATH "mul",
       "multiplies " W_SRC1 W_AND W_SRC2 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));

static void nat_math_mul_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise(vm, arguments, 2, multiply);
}

// math.div and math.muldiv: dest[i] = a[i] * b[i] / c[i] in 32 bits, for
// the layout &dest, &a, &b, &c, N, or &dest, &a, &c, N without a factor b
// (math.div). A zero c[i] stops the VM before dest[i] is written.
static void divide_elementwise(vm_state *vm, const int16_t *arguments, bool with_factor)
{
    int16_t *spans[4];
    uint16_t sources = with_factor ? 3 : 2;
    uint16_t length = nat_size_after(arguments, sources + 1);
    if (!nat_spans(vm, arguments, sources + 1, length, spans))
        return;
    int16_t *dest = spans[0];
    const int16_t *a = spans[1];
    const int16_t *b = spans[2]; // read only with_factor
    const int16_t *c = spans[sources];
    for (uint16_t i = 0; i < length; ++i) {
        int16_t divisor = c[i];
        if (divisor == 0) {
            vm_error_division_by_zero(vm);
            return;
        }
        // |a * b| <= 2^30 fits, and so does its quotient by -1; without b,
        // -32768 / -1 wraps instead of trapping.
        int32_t dividend = with_factor ? (int32_t)a[i] * b[i] : a[i];
        dest[i] = nat_wrap(dividend / divisor);
    }
}

NATIVE(math_div,
       4,
       W_MATH "div",
       "divides " W_SRC1 W_BY W_SRC2 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));

static void nat_math_div_function(vm_state *vm, const int16_t *arguments)
{
    divide_elementwise(vm, arguments, false);
}

NATIVE(math_min,
       4,
       W_MATH "min",
       W_WRITE "s" W_THE "minimum" W_OF W_SRC1 W_AND W_SRC2 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));

static void nat_math_min_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise(vm, arguments, 2, minimum);
}

NATIVE(math_max,
       4,
       W_MATH "max",
       W_WRITE "s" W_THE "maximum" W_OF W_SRC1 W_AND W_SRC2 W_TO W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC1) P(N, W_SRC2));

static void nat_math_max_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise(vm, arguments, 2, maximum);
}

NATIVE(math_clamp,
       5,
       W_MATH "clamp",
       "clamp " W_SRC W_TO "low/high bounds into " W_DEST "," W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, W_SRC) P(N, "low") P(N, "high"));

static void nat_math_clamp_function(vm_state *vm, const int16_t *arguments)
{
    int16_t *spans[4];
    uint16_t length = nat_size_after(arguments, 4);
    if (!nat_spans(vm, arguments, 4, length, spans))
        return;
    int16_t *dest = spans[0];
    const int16_t *src = spans[1];
    const int16_t *low = spans[2];
    const int16_t *high = spans[3];
    for (uint16_t i = 0; i < length; ++i) {
        int16_t value = src[i];
        if (value > high[i])
            dest[i] = high[i];
        else if (value < low[i])
            dest[i] = low[i];
        else
            dest[i] = value;
    }
}

NATIVE(math_dot,
       5,
       W_MATH "dot",
       W_WRITE "s" W_THE "dot product" W_OF W_SRC1 W_AND W_SRC2 W_TO W_DEST ", after a " W_SHIFT,
       P(1, W_DEST) P(N, W_SRC1) P(N, W_SRC2) P(1, W_SHIFT));

static void nat_math_dot_function(vm_state *vm, const int16_t *arguments)
{
    int16_t *dest = vm_variables(vm, (uint16_t)arguments[0], 1);
    if (dest == NULL)
        return;
    int16_t *sources[2];
    uint16_t length = nat_size_after(arguments, 4);
    if (!nat_spans(vm, arguments + 1, 2, length, sources))
        return;
    const int16_t *shift_variable = vm_variables(vm, (uint16_t)arguments[3], 1);
    if (shift_variable == NULL)
        return;
    int16_t shift = *shift_variable;

    // Summed unsigned so that overflow wraps as upstream's 32-bit sum does.
    uint32_t sum = 0;
    for (uint16_t i = 0; i < length; ++i)
        sum += (uint32_t)((int32_t)sources[0][i] * sources[1][i]);
    int32_t accumulator = (int32_t)sum;

    // Upstream leaves shifts outside 0 ... 32 to the processor; we define
    // them (bytecode.md §11): negative is no shift, 32 keeps the sign.
    if (shift > DOT_ACCUMULATOR_BITS) {
        *dest = 0;
    } else {
        if (shift < 0)
            shift = 0;
        // Shifting by 31 already leaves only the sign.
        if (shift == DOT_ACCUMULATOR_BITS)
            shift = DOT_ACCUMULATOR_BITS - 1;
        *dest = nat_wrap(accumulator >> shift);
    }
}

NATIVE(math_stat,
       5,
       W_MATH "stat",
       W_PERFORMS "statistics on " W_SRC,
       P(N, W_SRC) P(1, "min") P(1, "max") P(1, "mean"));

static void nat_math_stat_function(vm_state *vm, const int16_t *arguments)
{
    uint16_t length = nat_size_after(arguments, 4);
    const int16_t *src = vm_variables(vm, (uint16_t)arguments[0], length);
    if (src == NULL)
        return;
    int16_t *outputs[3];
    if (!nat_spans(vm, arguments + 1, 3, 1, outputs))
        return;
    int16_t *min = outputs[0];
    int16_t *max = outputs[1];
    int16_t *mean = outputs[2];
    if (length == 0)
        return;

    // The outputs may alias each other or src: compare with their current
    // contents, as upstream does, rather than with local copies.
    *min = src[0];
    *max = src[0];
    int32_t sum = src[0];
    for (uint16_t i = 1; i < length; ++i) {
        int16_t value = src[i];
        if (value < *min)
            *min = value;
        if (value > *max)
            *max = value;
        sum += value;
    }
    *mean = (int16_t)(sum / (int32_t)length);
}

NATIVE(math_argbounds,
       4,
       W_MATH "argbounds",
       "get" W_THE "indices (argmin, argmax)" W_OF "the limit " W_VALUE "s" W_OF W_SRC,
       P(N, W_SRC) P(1, "argmin") P(1, "argmax"));

static void nat_math_argbounds_function(vm_state *vm, const int16_t *arguments)
{
    uint16_t length = nat_size_after(arguments, 3);
    const int16_t *src = vm_variables(vm, (uint16_t)arguments[0], length);
    if (src == NULL)
        return;
    int16_t *outputs[2];
    if (!nat_spans(vm, arguments + 1, 2, 1, outputs))
        return;
    int16_t *argmin = outputs[0];
    int16_t *argmax = outputs[1];

    // An output is only written when it changes; src[i] is read once, before
    // argmin is written, since the outputs may alias src (upstream's order).
    int16_t lowest = INT16_MAX;
    int16_t highest = INT16_MIN;
    for (uint16_t i = 0; i < length; ++i) {
        int16_t value = src[i];
        if (value < lowest) {
            lowest = value;
            *argmin = (int16_t)i;
        }
        if (value > highest) {
            highest = value;
            *argmax = (int16_t)i;
        }
    }
}

NATIVE(math_sort, 2, W_MATH "sort", "sort " W_ARRAY " in place", P(N, W_ARRAY));

static void nat_math_sort_function(vm_state *vm, const int16_t *arguments)
{
    uint16_t length = nat_size_after(arguments, 1);
    int16_t *array = vm_variables(vm, (uint16_t)arguments[0], length);
    if (array == NULL)
        return;
    // Shell sort: insertion sorts over shrinking gaps, small code and no
    // recursion; any correct sort gives upstream's result.
    for (uint16_t gap = length / 2; gap > 0; gap /= 2) {
        for (uint16_t i = gap; i < length; ++i) {
            int16_t value = array[i];
            uint16_t j = i;
            while (j >= gap && array[j - gap] > value) {
                array[j] = array[j - gap];
                j -= gap;
            }
            array[j] = value;
        }
    }
}

NATIVE(math_muldiv,
       5,
       W_MATH "muldiv",
       W_PERFORMS W_DEST " = (a*b)/c in 32 bits" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "a") P(N, "b") P(N, "c"));

static void nat_math_muldiv_function(vm_state *vm, const int16_t *arguments)
{
    divide_elementwise(vm, arguments, true);
}

NATIVE(math_atan2,
       4,
       W_MATH "atan2",
       W_PERFORMS W_DEST " = atan2(y,x)" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "y") P(N, "x"));

static void nat_math_atan2_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise(vm, arguments, 2, nat_atan2);
}

// nat_sin and nat_cos as element-wise operations (nat_internal.h).
static int16_t sine_of(int16_t angle, int16_t same)
{
    (void)same;
    return nat_sin(angle);
}

static int16_t cosine_of(int16_t angle, int16_t same)
{
    (void)same;
    return nat_cos(angle);
}

NATIVE(math_sin,
       3,
       W_MATH "sin",
       W_PERFORMS W_DEST " = sin(x)" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "x"));

static void nat_math_sin_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise(vm, arguments, 1, sine_of);
}

NATIVE(math_cos,
       3,
       W_MATH "cos",
       W_PERFORMS W_DEST " = cos(x)" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "x"));

static void nat_math_cos_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise(vm, arguments, 1, cosine_of);
}

NATIVE(math_rot2,
       3,
       W_MATH "rot2",
       "rotates v" W_OF "angle a" W_TO W_DEST,
       P(2, W_DEST) P(2, "v") P(1, "a"));

static void nat_math_rot2_function(vm_state *vm, const int16_t *arguments)
{
    int16_t *vectors[2];
    if (!nat_spans(vm, arguments, 2, 2, vectors))
        return;
    const int16_t *angle = vm_variables(vm, (uint16_t)arguments[2], 1);
    if (angle == NULL)
        return;
    int16_t *dest = vectors[0];
    // Everything is read before dest is written: they may overlap.
    int32_t x = vectors[1][0];
    int32_t y = vectors[1][1];
    int32_t cosine = nat_cos(*angle);
    int32_t sine = nat_sin(*angle);
    // Each product is at most 2^30 in magnitude, so the sums fit in 32 bits.
    dest[0] = nat_wrap((cosine * x - sine * y) >> NAT_SINE_FRACTION_BITS);
    dest[1] = nat_wrap((cosine * y + sine * x) >> NAT_SINE_FRACTION_BITS);
}

NATIVE(math_sqrt,
       3,
       W_MATH "sqrt",
       W_PERFORMS W_DEST " = sqrt(x)" W_ELEMENT_BY_ELEMENT,
       P(N, W_DEST) P(N, "x"));

static void nat_math_sqrt_function(vm_state *vm, const int16_t *arguments)
{
    int16_t *spans[2];
    uint16_t length = nat_size_after(arguments, 2);
    if (!nat_spans(vm, arguments, 2, length, spans))
        return;
    for (uint16_t i = 0; i < length; ++i) {
        int16_t value = spans[1][i];
        if (value < 0) {
            vm_error_node_specific(vm, "Negative input to sqrt");
            return;
        }
        spans[0][i] = nat_sqrt(value);
    }
}

NATIVE(math_rand, 2, W_MATH "rand", W_FILL " " W_ARRAY " with random " W_VALUE "s", P(N, W_DEST));

static void nat_math_rand_function(vm_state *vm, const int16_t *arguments)
{
    uint16_t length = nat_size_after(arguments, 1);
    int16_t *dest = vm_variables(vm, (uint16_t)arguments[0], length);
    if (dest == NULL)
        return;
    for (uint16_t i = 0; i < length; ++i) {
        vm->random_state =
          (uint16_t)((uint32_t)RAND_MULTIPLIER * vm->random_state + RAND_INCREMENT);
        dest[i] = (int16_t)vm->random_state;
    }
}

static const vm_native math_natives[] = {
    NAT_RECORD(math_copy),      NAT_RECORD(math_fill), NAT_RECORD(math_addscalar),
    NAT_RECORD(math_add),       NAT_RECORD(math_sub),  NAT_RECORD(math_mul),
    NAT_RECORD(math_div),       NAT_RECORD(math_min),  NAT_RECORD(math_max),
    NAT_RECORD(math_clamp),     NAT_RECORD(math_dot),  NAT_RECORD(math_stat),
    NAT_RECORD(math_argbounds), NAT_RECORD(math_sort), NAT_RECORD(math_muldiv),
    NAT_RECORD(math_atan2),     NAT_RECORD(math_sin),  NAT_RECORD(math_cos),
    NAT_RECORD(math_rot2),      NAT_RECORD(math_sqrt), NAT_RECORD(math_rand),
};

const vm_native_module nat_math_module = NAT_MODULE(math_natives);
