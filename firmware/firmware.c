// The main loop: bytes from the link into the node, the actuator variables
// to the robot's devices and their sensors' values to the variables, the
// local events, and the node's poll (VM and protocol). Written against
// hal.h and the robot's package only, so the same code runs for every robot
// on every chip and in the host emulation.

#include "firmware.h"

#include "store/bytecode_store.h"

// The link must keep a whole frame of what arrives while the main loop waits
// for a frame to be sent, the store must hold the whole bytecode memory, and
// the variables must hold the VM's own and the robot's.
typedef char link_receives_a_whole_frame[HAL_LINK_RECEIVE_CAPACITY >= NODE_MAX_FRAME ? 1 : -1];
typedef char
  store_holds_the_bytecode[STORE_BYTECODE_CAPACITY_WORDS >= FIRMWARE_BYTECODE_WORDS ? 1 : -1];
typedef char variables_hold_the_named_ones[ROBOT_NAMED_WORDS > VM_NAMED_ARGS ? 1 : -1];
typedef char local_events_fit_a_word[ROBOT_LOCAL_EVENT_COUNT <= 16 ? 1 : -1];

// Moves received bytes from the link straight into the node's frame, never
// more than the frame lacks so that none has to wait anywhere between the
// two, until the link is empty or a whole frame waits for the node. Returns
// whether the node stopped taking them (the link may hold more for after
// node_poll).
static bool receive_from_link(firmware_state *firmware, uint32_t now)
{
    uint16_t wanted = node_receive_wanted(&firmware->node, now);

    while (wanted > 0) {
        uint16_t count =
          hal_link_receive(firmware->board, node_receive_place(&firmware->node), wanted);
        if (count == 0)
            return false;
        wanted = node_receive_placed(&firmware->node, count, now);
    }
    return true;
}

// The node streams its frames to the link's transmit buffer, which may be
// smaller than a frame: this waits, in order, for the link's interrupt to
// drain it. Meanwhile received bytes go on into the node's frame whenever
// it takes them (not while it handles one: node_receive_ready), so that the
// link's receive buffer fills only while the node holds a whole frame.
// node_poll handles a frame completed here after its VM run, as any other.
static void send_to_link(void *context, const uint8_t *bytes, uint16_t count, bool frame_complete)
{
    firmware_state *firmware = context;

    (void)frame_complete;
    for (;;) {
        uint16_t taken = hal_link_send(firmware->board, bytes, count);
        bytes += taken;
        count = (uint16_t)(count - taken);
        if (count == 0)
            return;
        receive_from_link(firmware, hal_milliseconds(firmware->board));
        hal_idle(firmware->board);
    }
}

// WRITE_BYTECODE: the program runs at the next boot. The node hands over
// its whole bytecode array; the zeros that end it are not stored, since the
// array they would come back into is cleared before a load: a short program
// takes the flash of one block, not of the whole slot (on the e-puck 2 NVM
// operations instead of 44, some 90 ms with the processor stalled). A failed
// save is reported as an error, which stops the VM like any other.
static void store_bytecode(void *context, const uint16_t *bytecode, uint16_t size)
{
    firmware_state *firmware = context;

    while (size > 1 && bytecode[size - 1] == 0)
        size--;
    if (!store_save_bytecode(firmware->board, bytecode, size))
        vm_error_node_specific(&firmware->node.vm, "could not store the bytecode");
}

// REBOOT: restart the chip (into the bootloader, which then boots the
// application unless a host talks to it).
static void reboot(void *context)
{
    firmware_state *firmware = context;

    hal_reset(firmware->board);
}

// A stored program starts at boot, running at once (bytecode.md §6.5), its
// `when` conditions cleared since the saved copy may hold was-true bits.
static void start_stored_program(firmware_state *firmware)
{
    uint16_t count;

    if (!store_load_bytecode(firmware->board, firmware->bytecode, FIRMWARE_BYTECODE_WORDS, &count))
        return;
    // The zeros store_bytecode left out.
    while (count < FIRMWARE_BYTECODE_WORDS)
        firmware->bytecode[count++] = 0;
    vm_reset(&firmware->node.vm);
    vm_command_run(&firmware->node.vm);
}

void firmware_init(firmware_state *firmware,
                   hal_board *board,
                   robot_devices *robot,
                   uint16_t node_id)
{
    vm_memory memory;
    node_transport transport;
    node_hooks hooks;

    firmware->board = board;
    firmware->robot = robot;
    robot_start(robot, board);
    memory.bytecode = firmware->bytecode;
    memory.bytecode_size = FIRMWARE_BYTECODE_WORDS;
    memory.variables = firmware->variables.words;
    memory.variables_size = FIRMWARE_VARIABLE_WORDS;
    memory.stack = firmware->stack;
    memory.stack_size = FIRMWARE_STACK_WORDS;
    memory.args_size = sizeof(firmware->variables.named.args) / sizeof(int16_t);
    transport.send = send_to_link;
    transport.context = firmware;
    hooks.write_bytecode = store_bytecode;
    hooks.reboot = reboot;
    hooks.suspend_to_ram = 0;
    hooks.context = firmware;
    node_init(&firmware->node, node_id, &robot_description, &memory, &transport, &hooks);
    robot_variables_at_boot(&firmware->variables.named);
    firmware->timer_period_ms = 0;
    firmware->next_timer_ms = 0;
    firmware->sensed_ms = (uint16_t)(hal_milliseconds(board) - 1u);
    start_stored_program(firmware);
}

// The local events the robot's devices ask for (bit i: event i).
static void raise_local_events(firmware_state *firmware, uint16_t events)
{
    uint16_t index;

    for (index = 0; index < ROBOT_LOCAL_EVENT_COUNT; index++) {
        if (events & (1u << index))
            node_raise_local_event(&firmware->node, index);
    }
}

// The robot's timer event every period its variable says (0 or less: never).
static void update_timer(firmware_state *firmware, uint32_t now)
{
    int16_t period = robot_timer_period_ms(&firmware->variables.named);

    if (period != firmware->timer_period_ms) {
        firmware->timer_period_ms = period;
        firmware->next_timer_ms = now + (uint32_t)(int32_t)period;
    }
    if (period <= 0 || (int32_t)(now - firmware->next_timer_ms) < 0)
        return;
    node_raise_local_event(&firmware->node, ROBOT_TIMER_EVENT);
    firmware->next_timer_ms += (uint32_t)(int32_t)period;
    if ((int32_t)(now - firmware->next_timer_ms) >= 0) // fell behind: do not catch up
        firmware->next_timer_ms = now + (uint32_t)(int32_t)period;
}

bool firmware_poll(firmware_state *firmware)
{
    uint32_t now = hal_milliseconds(firmware->board);
    bool link_waiting = receive_from_link(firmware, now);
    bool busy;

    robot_actuate(firmware->robot, &firmware->variables.named);
    // The sensors' values change with time only (the chip's interrupts fill
    // them in, the host's world moves between milliseconds): a pass within
    // the same millisecond would read them again for nothing, and a node
    // busy with a stream of messages passes many times a millisecond.
    if ((uint16_t)now != firmware->sensed_ms) {
        firmware->sensed_ms = (uint16_t)now;
        raise_local_events(firmware, robot_sense(firmware->robot, &firmware->variables.named));
    }
    update_timer(firmware, now);

    busy = node_poll(&firmware->node, now);
    return busy || link_waiting;
}

void firmware_start_program(firmware_state *firmware, const uint16_t *bytecode, uint16_t count)
{
    vm_set_bytecode(&firmware->node.vm, 0, bytecode, count);
    vm_command_run(&firmware->node.vm);
}
