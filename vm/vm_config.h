// Feature switches of the VM. A target sets them in its own config header,
// named by VM_TARGET_CONFIG on the compiler's command line; these are the
// defaults. Memory sizes are not here: the node gives the VM its memory.

#ifndef VM_CONFIG_H
#define VM_CONFIG_H

#ifdef VM_TARGET_CONFIG
#include VM_TARGET_CONFIG
#endif

// Dispatch through a table of label addresses (a GNU extension) instead of a
// switch. The switch is the reference: XC16's support of `&&label` is
// unverified, so the dsPIC target keeps it off.
#ifndef VM_USE_COMPUTED_GOTO
#define VM_USE_COMPUTED_GOTO 0
#endif

// Most stack words a native function may take (parameters and size words).
#ifndef VM_MAX_NATIVE_ARGUMENTS
#define VM_MAX_NATIVE_ARGUMENTS 16
#endif

#endif
