// What the files of the standard natives share: the functions that fetch
// arguments, the macros that write the natives' descriptions, beside their
// bodies, and the module of records at the end of each file.
// Not for use outside native_functions/.

#ifndef NAT_INTERNAL_H
#define NAT_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "nat_standard.h"
#include "vm.h"

// The low 16 bits of `value` as a signed word: Aseba's wrapping arithmetic.
static inline int16_t nat_wrap(int32_t value)
{
    return (int16_t)(uint16_t)(uint32_t)value;
}

// Fetches `count` spans of `length` words whose addresses are
// arguments[0 .. count-1] into spans[]. Returns false, the VM stopped with an
// error, as soon as one does not fit in the variables.
bool nat_spans(vm_state *vm,
               const int16_t *arguments,
               uint16_t count,
               uint16_t length,
               int16_t **spans);

// The template size word `word` as a length. A negative word becomes a
// length larger than any memory, which vm_variables refuses.
static inline uint16_t nat_length(int16_t word)
{
    return (uint16_t)word;
}

// The size word N of a native with `parameter_count` parameters, which the
// VM pops right after their addresses (bytecode.md §9).
static inline uint16_t nat_size_after(const int16_t *arguments, uint16_t parameter_count)
{
    return nat_length(arguments[parameter_count]);
}

// An element-wise operation. One of one operand ignores `right`: the
// natives of one source share the loop of two (less code).
typedef int16_t (*nat_operation)(int16_t left, int16_t right);

// dest[i] = operation(src1[i], src2[i]) for the layout &dest, &src1, &src2,
// N, or operation(src[i], src[i]) for &dest, &src, N when `sources` is 1, in
// increasing i.
void nat_elementwise(vm_state *vm,
                     const int16_t *arguments,
                     uint16_t sources,
                     nat_operation operation);

// --- description records -----------------------------------------------------

// Parts of a packed description (vm.h): the documentation's mark, and a
// parameter of size N, M or P (templates -1, -2, -3) or 1, 2, 4 or 5 words,
// as P(N, W_DEST) (a size byte is the size plus VM_NATIVE_SIZE_BIAS).
#define DOC           "\x1F"
#define SIZE_P        "\x0D"
#define SIZE_M        "\x0E"
#define SIZE_N        "\x0F"
#define SIZE_1        "\x11"
#define SIZE_2        "\x12"
#define SIZE_4        "\x14"
#define SIZE_5        "\x15"
#define P(size, name) SIZE_##size name

// Stack-words bytes that start a packed description (vm.h, vm_native).
#define STACK_2 "\x02"
#define STACK_3 "\x03"
#define STACK_4 "\x04"
#define STACK_5 "\x05"
#define STACK_6 "\x06"
#define STACK_7 "\x07"

// One native's packed description, nat_<identifier>_description: its stack
// words, those of bytecode.md §9 (parameters + size-0 parameters + distinct
// templates; the tests check them for every entry), its name, documentation
// and parameters (P(...) P(...)). Its function, beside it, is
// nat_<identifier>_function. Both are static: the file's module (below)
// is what the rest of the firmware sees, and a native left out of it is an
// unused static, which the compiler reports.
#define NATIVE(identifier, stack_words, name, documentation, parameters)                           \
    static const char nat_##identifier##_description[] =                                           \
      STACK_##stack_words name DOC documentation parameters

// The record (vm_native) of the native defined with NATIVE(identifier, ...).
#define NAT_RECORD(identifier)                                                                     \
    {                                                                                              \
        nat_##identifier##_function, nat_##identifier##_description                                \
    }

// A file's module (vm_native_module) over its array of records, which it
// lists at its end in NATIVE_CALL order: the count follows the array.
#define NAT_MODULE(records)                                                                        \
    {                                                                                              \
        records, sizeof records / sizeof records[0]                                                \
    }

#endif
