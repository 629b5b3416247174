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

void nat_elementwise_unary(vm_state *vm, const int16_t *arguments, nat_unary_operation operation)
{
    int16_t *spans[2];
    uint16_t length = nat_size_after(arguments, 2);
    if (!nat_spans(vm, arguments, 2, length, spans))
        return;
    for (uint16_t i = 0; i < length; ++i)
        spans[0][i] = operation(spans[1][i]);
}

void nat_elementwise_binary(vm_state *vm, const int16_t *arguments, nat_binary_operation operation)
{
    int16_t *spans[3];
    uint16_t length = nat_size_after(arguments, 3);
    if (!nat_spans(vm, arguments, 3, length, spans))
        return;
    for (uint16_t i = 0; i < length; ++i)
        spans[0][i] = operation(spans[1][i], spans[2][i]);
}
