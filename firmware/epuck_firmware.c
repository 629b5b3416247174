// The e-puck's main loop: bytes from the link into the node, the actuator
// variables to the drivers and the sensors' values to the variables (in the
// upstream firmware's order, hardware §6.1), the local events, and the
// node's poll (VM and protocol). Written against hal.h only,
// so the same code runs on the robot and in the host emulation.

#include "epuck_firmware.h"

#include "drivers/epuck/epuck_battery.h"
#include "drivers/epuck/epuck_selector.h"
#include "bootloader/bytecode_store.h"
#include "epuck_natives.h"

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

const node_description epuck_description = {
    EPUCK_NAME,          NODE_PROTOCOL_VERSION,
    epuck_variables,     sizeof(epuck_variables) / sizeof(epuck_variables[0]),
    epuck_local_events,  EPUCK_LOCAL_EVENT_COUNT,
    &epuck_native_table,
};

// The node streams its frames to the board's link.
static void send_to_link(void *context, const uint8_t *bytes, uint16_t count, bool frame_complete)
{
    epuck_firmware *firmware = context;

    (void)frame_complete;
    hal_link_send(firmware->board, bytes, count);
}

// WRITE_BYTECODE: the program runs at the next boot. A failed save is
// reported as an error, which stops the VM like any other.
static void store_bytecode(void *context, const uint16_t *bytecode, uint16_t size)
{
    epuck_firmware *firmware = context;

    if (!epuck_store_save_bytecode(firmware->board, bytecode, size))
        vm_error_node_specific(&firmware->node.vm, "could not store the bytecode");
}

// REBOOT: restart the chip (into the bootloader, which then boots the
// application unless a host talks to it).
static void reboot(void *context)
{
    epuck_firmware *firmware = context;

    hal_reset(firmware->board);
}

// A stored program starts at boot, running at once (bytecode.md §6.5), its
// `when` conditions cleared since the saved copy may hold was-true bits.
static void start_stored_program(epuck_firmware *firmware)
{
    uint16_t count;

    if (!epuck_store_load_bytecode(
          firmware->board, firmware->bytecode, EPUCK_BYTECODE_WORDS, &count))
        return;
    vm_reset(&firmware->node.vm);
    vm_command_run(&firmware->node.vm);
}

// Starts every driver: actuators off, the analog scan (whose first second
// and a half calibrates the proximity sensors and accelerometer), the
// camera and the remote (hardware §6.6).
static void start_drivers(epuck_firmware *firmware, hal_board *board)
{
    epuck_motor_init(&firmware->left_motor, board, EPUCK_MOTOR_LEFT);
    epuck_motor_init(&firmware->right_motor, board, EPUCK_MOTOR_RIGHT);
    epuck_leds_init(&firmware->leds, board);
    epuck_proximity_init(&firmware->proximity, board);
    epuck_accelerometer_init(&firmware->accelerometer, board);
    epuck_microphones_init(&firmware->microphones, board);
    epuck_analog_start(&firmware->analog,
                       board,
                       &firmware->proximity,
                       &firmware->accelerometer,
                       &firmware->microphones);
    epuck_camera_init(&firmware->camera, board);
    epuck_rc5_init(&firmware->rc5, board);
}

void epuck_firmware_init(epuck_firmware *firmware, hal_board *board, uint16_t node_id)
{
    vm_memory memory;
    node_transport transport;
    node_hooks hooks;

    firmware->board = board;
    if (node_id == 0)
        node_id = epuck_store_node_id(board, epuck_selector_read(board));
    start_drivers(firmware, board);
    memory.bytecode = firmware->bytecode;
    memory.bytecode_size = EPUCK_BYTECODE_WORDS;
    memory.variables = firmware->variables.words;
    memory.variables_size = EPUCK_VARIABLES_WORDS;
    memory.stack = firmware->stack;
    memory.stack_size = EPUCK_STACK_WORDS;
    memory.args_size = sizeof(firmware->variables.named.args) / sizeof(int16_t);
    transport.send = send_to_link;
    transport.context = firmware;
    hooks.write_bytecode = store_bytecode;
    hooks.reboot = reboot;
    hooks.suspend_to_ram = 0;
    hooks.context = firmware;
    node_init(&firmware->node, node_id, &epuck_description, &memory, &transport, &hooks);
    firmware->variables.named.cam_line[0] = EPUCK_CAMERA_DEFAULT_LINE;
    firmware->link_start = 0;
    firmware->link_count = 0;
    firmware->timer_period_ms = 0;
    firmware->next_timer_ms = 0;
    start_stored_program(firmware);
}

// Speeds and LEDs from the variables to the motors and LEDs; the speeds are
// written back clamped to the motors' range.
static void update_actuators(epuck_firmware *firmware)
{
    epuck_named_variables *named = &firmware->variables.named;
    uint16_t led;

    epuck_motor_set_speed(&firmware->left_motor, named->left_speed[0]);
    epuck_motor_set_speed(&firmware->right_motor, named->right_speed[0]);
    named->left_speed[0] = epuck_motor_speed(&firmware->left_motor);
    named->right_speed[0] = epuck_motor_speed(&firmware->right_motor);
    for (led = 0; led < EPUCK_RING_LED_COUNT; led++)
        epuck_leds_set(&firmware->leds, led, named->leds[led] != 0);
}

// Sensor values into the variables, raising the events of new ones.
static void update_sensors(epuck_firmware *firmware)
{
    epuck_named_variables *named = &firmware->variables.named;
    uint8_t toggle;
    uint8_t address;
    uint8_t command;

    if (epuck_proximity_take(&firmware->proximity, named->prox, named->ambient))
        node_raise_local_event(&firmware->node, EPUCK_EVENT_ir_sensors);
    epuck_accelerometer_read(&firmware->accelerometer, named->acc);
    epuck_microphones_read(&firmware->microphones, named->mic);
    if (epuck_camera_capture(
          &firmware->camera, named->cam_line[0], named->cam_red, named->cam_green, named->cam_blue))
        node_raise_local_event(&firmware->node, EPUCK_EVENT_camera);
    named->steps_left[0] = epuck_motor_steps(&firmware->left_motor);
    named->steps_right[0] = epuck_motor_steps(&firmware->right_motor);
    named->battery[0] = epuck_battery_ok(firmware->board) ? 1 : 0;
    named->selector[0] = (int16_t)epuck_selector_read(firmware->board);
    if (epuck_rc5_take(&firmware->rc5, &toggle, &address, &command))
        named->rc5[0] = command;
}

// The `timer` event every timer.period milliseconds (0 or less: never).
static void update_timer(epuck_firmware *firmware, uint32_t now)
{
    int16_t period = firmware->variables.named.timer_period[0];

    if (period != firmware->timer_period_ms) {
        firmware->timer_period_ms = period;
        firmware->next_timer_ms = now + (uint32_t)(int32_t)period;
    }
    if (period <= 0 || (int32_t)(now - firmware->next_timer_ms) < 0)
        return;
    node_raise_local_event(&firmware->node, EPUCK_EVENT_timer);
    firmware->next_timer_ms += (uint32_t)(int32_t)period;
    if ((int32_t)(now - firmware->next_timer_ms) >= 0) // fell behind: do not catch up
        firmware->next_timer_ms = now + (uint32_t)(int32_t)period;
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

    update_actuators(firmware);
    update_sensors(firmware);
    update_timer(firmware, now);

    busy = node_poll(&firmware->node, now);
    return busy || firmware->link_count != 0;
}

void epuck_firmware_start_program(epuck_firmware *firmware,
                                  const uint16_t *bytecode,
                                  uint16_t count)
{
    vm_set_bytecode(&firmware->node.vm, 0, bytecode, count);
    vm_command_run(&firmware->node.vm);
}
