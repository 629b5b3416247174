// How the standard natives reach their arguments: every address comes from
// the bytecode, so every span goes through vm_variables' bounds check.

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
