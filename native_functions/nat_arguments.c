// How the standard natives reach their arguments: every address comes from
// the bytecode, so every span goes through vm_variables' bounds check. And
// the element-wise loops that many natives share.

#include "nat_internal.h"

#include <stddef.h>

bool nat_spans(vm_state *vm,
               const int16_t *arguments,
               uint16_t count,
               uint16_t length,
               int16_t **spans)
{
    for (uint16_t i = 0; i < count; ++i) {
        spans[i] = vm_variables(vm, (uint16_t)arguments[i], length);
        // One error is enough: the VM is stopped, the caller returns at once.
        if (spans[i] == NULL)
            return false;
    }
    return true;
}

void nat_elementwise(vm_state *vm,
                     const int16_t *arguments,
                     uint16_t sources,
                     nat_operation operation)
{
    int16_t *spans[3];
    uint16_t length = nat_size_after(arguments, sources + 1);
    if (!nat_spans(vm, arguments, sources + 1, length, spans))
        return;
    const int16_t *right = spans[sources];
    for (uint16_t i = 0; i < length; ++i)
        spans[0][i] = operation(spans[1][i], right[i]);
}
