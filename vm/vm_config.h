// The VM's switches. They are the target's, in its one configuration header
// (boards/<board>/<board>_config.h), which every firmware and host build
// names with TARGET_CONFIG (docs/porting.md); this file includes it and
// stops a build whose target does not give them. Memory sizes are not
// here: the node gives the VM its memory.
//
//   VM_USE_COMPUTED_GOTO     1: dispatch through a table of label addresses
//                            (a GNU extension), 0: through a switch, the
//                            reference (XC16's support of `&&label` is
//                            unverified, so the dsPIC target keeps it off)
//   VM_MAX_NATIVE_ARGUMENTS  most stack words a native function may take
//                            (parameters and size words)

#ifndef VM_CONFIG_H
#define VM_CONFIG_H

#ifndef TARGET_CONFIG
#error "TARGET_CONFIG must name the target's configuration header (docs/porting.md)"
#endif
#include TARGET_CONFIG

#if !defined(VM_USE_COMPUTED_GOTO) || !defined(VM_MAX_NATIVE_ARGUMENTS)
#error "the target's configuration must give VM_USE_COMPUTED_GOTO and VM_MAX_NATIVE_ARGUMENTS"
#endif

#endif
