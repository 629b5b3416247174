// Sizes and switches of the e-puck firmware, in one place. The dsPIC build
// names this file as VM_TARGET_CONFIG, so the VM and node defaults can be
// overridden here too. Memory sizes and variables are in epuck_description.h.

#ifndef EPUCK_CONFIG_H
#define EPUCK_CONFIG_H

// Bytes taken from the link per main-loop pass.
#define EPUCK_LINK_CHUNK 32

// The node id is (selector & EPUCK_SELECTOR_NODE_MASK) + 1 (hardware §6.1,
// §6.6) unless the caller gives one.
#define EPUCK_SELECTOR_NODE_MASK 0x7u

#endif
