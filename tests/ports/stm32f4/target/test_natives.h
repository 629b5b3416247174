/* The host tests' native tables and node presets, for the harness image
 * (test_natives.c). */

#ifndef TEST_NATIVES_H
#define TEST_NATIVES_H

#include "node.h"
#include "vm.h"

extern const vm_native_table harness_natives;
extern const node_description tiny_description;
extern const node_description refnode_description;

#endif
