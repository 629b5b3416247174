// The native functions our e-puck exports, in NATIVE_CALL order: the
// standard library, then the DSP natives. One table for the firmware (which
// calls and describes them) and the compiler's e-puck target.

#ifndef EPUCK_NATIVES_H
#define EPUCK_NATIVES_H

#include "vm/vm.h"

extern const vm_native_table epuck_native_table;

#endif
