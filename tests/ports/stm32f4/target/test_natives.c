/* The native tables and node descriptions of the host tests, in C for the
 * harness image: tests/support/vm_harness.cpp's twelve test natives and
 * tests/node/node_harness.cpp's `tiny` and `refnode` presets, with the same
 * names and semantics. The host checks that each preset's description has
 * the fingerprint of the host's before a trace runs (remote_node.cpp); the
 * natives' behaviour is what the VM program tests expect of them. */

#include "test_natives.h"

#include "nat_standard.h"
#include "node_protocol.h"

/* --- tests/support/vm_harness.cpp ------------------------------------------------ */

static void native_subtract(vm_state *vm, const int16_t *arguments)
{
    int16_t *dest = vm_variables(vm, (uint16_t)arguments[0], 1);
    int16_t *a = vm_variables(vm, (uint16_t)arguments[1], 1);
    int16_t *b = vm_variables(vm, (uint16_t)arguments[2], 1);
    if (dest && a && b)
        *dest = (int16_t)(*a - *b);
}

static void native_fail(vm_state *vm, const int16_t *arguments)
{
    (void)arguments;
    vm_error_node_specific(vm, "test failure");
}

static void native_fill(vm_state *vm, const int16_t *arguments)
{
    uint16_t size = (uint16_t)arguments[2];
    int16_t *dest = vm_variables(vm, (uint16_t)arguments[0], size);
    int16_t *value = vm_variables(vm, (uint16_t)arguments[1], 1);
    uint16_t i;
    for (i = 0; dest && value && i < size; i++)
        dest[i] = *value;
}

static void native_reach(vm_state *vm, const int16_t *arguments)
{
    uint16_t length = (uint16_t)arguments[1];
    int16_t *first = vm_variables(vm, (uint16_t)arguments[0], length);
    uint16_t i;
    for (i = 0; first && i < length; i++)
        first[i] = 7;
}

static void native_yield(vm_state *vm, const int16_t *arguments)
{
    (void)arguments;
    vm->flags &= (uint16_t)~VM_FLAG_EVENT_RUNNING;
}

static void native_stat(vm_state *vm, const int16_t *arguments)
{
    uint16_t size = (uint16_t)arguments[4];
    const int16_t *source = vm_variables(vm, (uint16_t)arguments[0], size);
    int16_t *outputs[3];
    int32_t low, high, sum = 0;
    uint16_t i;

    for (i = 0; i < 3; i++)
        outputs[i] = vm_variables(vm, (uint16_t)arguments[1 + i], 1);
    if (!source || !outputs[0] || !outputs[1] || !outputs[2] || size == 0)
        return;
    low = high = source[0];
    for (i = 0; i < size; i++) {
        low = source[i] < low ? source[i] : low;
        high = source[i] > high ? source[i] : high;
        sum += source[i];
    }
    *outputs[0] = (int16_t)low;
    *outputs[1] = (int16_t)high;
    *outputs[2] = (int16_t)(sum / size);
}

/* Described by their stack words and names alone (a packed description,
   vm.h). */
static const char fail_description[] = "\x00test.fail";
static const vm_native harness_native_list[] = {
    { native_subtract, "\x03test.subtract" }, { native_fill, "\x03test.fill" },
    { native_fail, fail_description },        { native_reach, "\x02test.reach" },
    { native_yield, "\x00test.yield" },       { native_fail, fail_description },
    { native_fail, fail_description },        { native_fail, fail_description },
    { native_fail, fail_description },        { native_fail, fail_description },
    { native_fail, fail_description },        { native_stat, "\x05test.stat" },
};
static const vm_native_module harness_module = { harness_native_list, 12 };
static const vm_native_module *const harness_modules[] = { &harness_module };
const vm_native_table harness_natives = { harness_modules, 1, 0 };

/* --- tests/node/node_harness.cpp ------------------------------------------------ */

static void test_sqrt(vm_state *vm, const int16_t *arguments)
{
    int16_t *x = vm_variables(vm, (uint16_t)arguments[0], 1);
    int32_t root = 0;
    if (x == 0)
        return;
    if (*x < 0) {
        vm_error_node_specific(vm, "Negative input to sqrt");
        return;
    }
    while ((root + 1) * (root + 1) <= *x)
        root++;
    *x = (int16_t)root;
}

static void test_fill(vm_state *vm, const int16_t *arguments)
{
    uint16_t size = (uint16_t)arguments[2];
    int16_t *value = vm_variables(vm, (uint16_t)arguments[1], 1);
    int16_t *dest;
    uint16_t i;
    if (value == 0)
        return;
    dest = vm_variables(vm, (uint16_t)arguments[0], size);
    if (dest == 0)
        return;
    for (i = 0; i < size; i++)
        dest[i] = *value;
}

/* Packed descriptions (vm.h): stack words, name, 0x1F and the
   documentation, then each parameter's size + 0x10 and its name. */
static const vm_native tiny_native_list[] = {
    { test_sqrt,
      "\x01test.sqrt\x1F"
      "integer square root\x11"
      "x" },
    { test_fill,
      "\x03test.fill\x1F"
      "fills dest with value\x0F"
      "dest\x11"
      "value" },
};
static const vm_native_module tiny_module = { tiny_native_list, 2 };
static const vm_native_module *const tiny_modules[] = { &tiny_module };
static const vm_native_table tiny_natives = { tiny_modules, 1, 0 };

static const node_named_variable tiny_variables[] = { { "id", 1 },
                                                      { "source", 1 },
                                                      { "args", 4 },
                                                      { "leds", 3 } };
static const node_local_event tiny_events[] = { { "timer", "periodic tick" },
                                                { "button", "pressed" } };
const node_description tiny_description = {
    "tinynode", NODE_PROTOCOL_VERSION, tiny_variables, 4, tiny_events, 2, &tiny_natives
};

static const node_named_variable refnode_variables[] = { { "id", 1 },
                                                         { "source", 1 },
                                                         { "args", 32 },
                                                         { "_productId", 1 },
                                                         { "timer.period", 1 } };
static const node_local_event refnode_events[] = { { "timer", "periodic timer" } };
const node_description refnode_description = {
    "refnode", NODE_PROTOCOL_VERSION, refnode_variables, 5, refnode_events, 1, &nat_standard_table
};
