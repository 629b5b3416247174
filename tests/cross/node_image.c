// The smallest program that uses the VM, the standard natives and the node
// the way a firmware does: linked with unused sections dropped, its size is
// what those layers cost in a real image (scripts/cross-check.sh).

#include "native_functions/nat_standard.h"
#include "native_functions/nat_words.h"
#include "vm/node.h"

static const vm_native_module *const modules[] = { NAT_STANDARD_MODULES };
static const vm_native_table native_table = { modules,
                                              sizeof modules / sizeof modules[0],
                                              nat_words };
static const node_named_variable variables[] = { { "id", 1 }, { "source", 1 }, { "args", 32 } };
static const node_local_event events[] = { { "tick", "a local event" } };
static const node_description description = {
    "probe", NODE_PROTOCOL_VERSION, variables, 3, events, 1, &native_table,
};

static void send(void *context, const uint8_t *bytes, uint16_t count, bool frame_complete)
{
    // Reached through a volatile so that the compiler keeps every byte.
    volatile uint8_t *sink = context;
    uint16_t i;

    for (i = 0; i < count; i++)
        *sink = bytes[i];
    *sink = frame_complete;
}

static void write_bytecode(void *context, const uint16_t *bytecode, uint16_t size)
{
    volatile uint16_t *sink = context;

    *sink = size ? bytecode[0] : 0;
}

static void reboot(void *context)
{
    (void)context;
}

static uint16_t bytecode[1024];
static int16_t memory[512];
static int16_t stack[32];
static node_state node;
static volatile uint8_t sink;
static volatile uint16_t word_sink;

int main(void)
{
    vm_memory layout = { bytecode, 1024, memory, 512, stack, 32, 32 };
    node_transport transport = { send, (void *)&sink };
    node_hooks hooks = { write_bytecode, reboot, reboot, (void *)&word_sink };
    uint32_t now = 0;

    node_init(&node, 1, &description, &layout, &transport, &hooks);
    for (;;) {
        uint8_t byte = sink;
        node_receive(&node, &byte, 1, now);
        node_raise_local_event(&node, 0);
        node_poll(&node, now++);
    }
}
