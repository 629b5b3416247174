// The interpreter compiled with computed-goto dispatch, so that the tests run
// both dispatch variants of the same source.
#define VM_USE_COMPUTED_GOTO 1
#include "vm/vm.c"
