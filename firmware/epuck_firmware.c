// The e-puck's main loop: bytes from the link into the node, the node's
// poll (VM and protocol), and the local events. Written against hal.h only,
// so the same code runs on the robot and in the host emulation.

#include "epuck_firmware.h"

#include "native_functions/nat_standard.h"

static const node_named_variable epuck_variables[] = {
#define EPUCK_VARIABLE_DESCRIPTION(identifier, name, size) { name, size },
    EPUCK_VARIABLE_LIST(EPUCK_VARIABLE_DESCRIPTION)
#undef EPUCK_VARIABLE_DESCRIPTION
};

enum epuck_local_event {
#define EPUCK_LOCAL_EVENT_INDEX(identifier, name, description) EPUCK_EVENT_##identifier,
    EPUCK_LOCAL_EVENT_LIST(EPUCK_LOCAL_EVENT_INDEX)
#undef EPUCK_LOCAL_EVENT_INDEX
      EPUCK_LOCAL_EVENT_COUNT
};

static const node_local_event epuck_local_events[] = {
#define EPUCK_LOCAL_EVENT_DESCRIPTION(identifier, name, description) { name, description },
    EPUCK_LOCAL_EVENT_LIST(EPUCK_LOCAL_EVENT_DESCRIPTION)
#undef EPUCK_LOCAL_EVENT_DESCRIPTION
};

static const vm_native *const epuck_native_list[] = { NAT_STANDARD_LIST };

static const vm_native_table epuck_natives = {
    epuck_native_list,
    sizeof(epuck_native_list) / sizeof(epuck_native_list[0]),
};

const node_description epuck_description = {
    EPUCK_NAME,         NODE_PROTOCOL_VERSION,
    epuck_variables,    sizeof(epuck_variables) / sizeof(epuck_variables[0]),
    epuck_local_events, EPUCK_LOCAL_EVENT_COUNT,
    &epuck_natives,
};

// The node streams its frames to the board's link.
static void send_to_link(void *context, const uint8_t *bytes, uint16_t count, bool frame_complete)
{
    epuck_firmware *firmware = context;

    (void)frame_complete;
    hal_link_send(firmware->board, bytes, count);
}

void epuck_firmware_init(epuck_firmware *firmware, hal_board *board, uint16_t node_id)
{
    vm_memory memory;
    node_transport transport;
    uint32_t now = hal_milliseconds(board);

    firmware->board = board;
    memory.bytecode = firmware->bytecode;
    memory.bytecode_size = EPUCK_BYTECODE_WORDS;
    memory.variables = firmware->variables.words;
    memory.variables_size = EPUCK_VARIABLES_WORDS;
    memory.stack = firmware->stack;
    memory.stack_size = EPUCK_STACK_WORDS;
    memory.args_size = sizeof(firmware->variables.named.args) / sizeof(int16_t);
    transport.send = send_to_link;
    transport.context = firmware;
    node_init(&firmware->node, node_id, &epuck_description, &memory, &transport, 0);
    firmware->link_start = 0;
    firmware->link_count = 0;
    firmware->next_ir_sensors_ms = now + EPUCK_IR_SENSORS_PERIOD_MS;
    firmware->next_camera_ms = now + EPUCK_CAMERA_PERIOD_MS;
}

// Whether the periodic deadline `*next` has passed; if so, schedules the next.
static bool period_elapsed(uint32_t now, uint32_t *next, uint32_t period)
{
    // Compared as a signed difference so that the clock may wrap.
    if ((int32_t)(now - *next) < 0)
        return false;
    *next += period;
    if ((int32_t)(now - *next) >= 0) // fell behind: do not try to catch up
        *next = now + period;
    return true;
}

bool epuck_firmware_poll(epuck_firmware *firmware)
{
    uint32_t now = hal_milliseconds(firmware->board);
    bool busy;

    if (firmware->link_count == 0) {
        firmware->link_start = 0;
        firmware->link_count =
          hal_link_receive(firmware->board, firmware->link_bytes, EPUCK_LINK_CHUNK);
    }
    if (firmware->link_count != 0) {
        uint16_t taken = node_receive(
          &firmware->node, firmware->link_bytes + firmware->link_start, firmware->link_count, now);
        firmware->link_start += taken;
        firmware->link_count -= taken;
    }

    if (period_elapsed(now, &firmware->next_ir_sensors_ms, EPUCK_IR_SENSORS_PERIOD_MS))
        node_raise_local_event(&firmware->node, EPUCK_EVENT_ir_sensors);
    if (period_elapsed(now, &firmware->next_camera_ms, EPUCK_CAMERA_PERIOD_MS))
        node_raise_local_event(&firmware->node, EPUCK_EVENT_camera);

    busy = node_poll(&firmware->node, now);
    return busy || firmware->link_count != 0;
}

void epuck_firmware_start_program(epuck_firmware *firmware, const uint16_t *bytecode,
                                  uint16_t count)
{
    vm_set_bytecode(&firmware->node.vm, 0, bytecode, count);
    vm_command_run(&firmware->node.vm);
}
