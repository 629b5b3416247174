// The interpreter compiled with switch dispatch, the reference that the
// dsPIC build uses (the host's aseba_vm uses computed goto), so that the
// tests run both dispatch variants of the same source.
#define VM_USE_COMPUTED_GOTO 0
#include "vm/vm.c"
