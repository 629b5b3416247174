// Feature switches of the VM, with their defaults. A target sets them in its
// one configuration header, which every firmware and host build names with
// TARGET_CONFIG (docs/porting.md); the VM alone also builds without one.
// Memory sizes are not here: the node gives the VM its memory.

#ifndef VM_CONFIG_H
#define VM_CONFIG_H

#ifdef TARGET_CONFIG
#include TARGET_CONFIG
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
