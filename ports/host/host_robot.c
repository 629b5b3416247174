// The simulated e-puck's reset sequence: bootloader, then firmware.

#include "host_robot.h"

#include "bootloader/boot_application.h"
#include "robots/epuck/devices/epuck_selector.h"
#include "store/bytecode_store.h"

void host_robot_init(host_robot *robot,
                     uint16_t node_id,
                     void (*link_output)(void *context, const uint8_t *bytes, uint16_t count),
                     void *link_context)
{
    host_board_init(&robot->board, link_output, link_context);
    robot->given_node_id = node_id;
    host_robot_update_node_id(robot);
    robot->mode = HOST_ROBOT_IN_BOOTLOADER;
    robot->resets = 0;
}

void host_robot_update_node_id(host_robot *robot)
{
    // As the chip's entry points (ports/dspic30/dspic30_application_main.c).
    robot->node_id =
      robot->given_node_id != HOST_ROBOT_NODE_ID_AT_BOOT
        ? robot->given_node_id
        : store_node_id(&robot->board, epuck_selector_node_id(epuck_selector_read(&robot->board)));
}

void host_robot_start_application(host_robot *robot)
{
    host_robot_update_node_id(robot);
    robot->mode = HOST_ROBOT_IN_APPLICATION;
    firmware_init(&robot->firmware, &robot->board, &robot->devices, robot->node_id);
}

// The bootloader's start, after power-on or a reset.
static void start_bootloader(host_robot *robot)
{
    robot->mode = HOST_ROBOT_IN_BOOTLOADER;
    host_robot_update_node_id(robot);
    boot_start(&robot->loader, &robot->board, robot->node_id);
}

void host_robot_power_on(host_robot *robot)
{
    uint32_t entry;
    if (boot_application_valid(&robot->board, &entry))
        host_robot_start_application(robot);
    else
        start_bootloader(robot);
}

void host_robot_reset(host_robot *robot)
{
    host_board_reset(&robot->board);
    robot->resets++;
    start_bootloader(robot);
}

bool host_robot_poll(host_robot *robot)
{
    bool busy = false;

    if (robot->mode == HOST_ROBOT_IN_APPLICATION)
        busy = firmware_poll(&robot->firmware);
    else if (boot_poll(&robot->loader) == BOOT_START_APPLICATION) {
        // The firmware's start-up sets the UART up again, which empties
        // it. Here that also keeps the firmware from starting in the
        // middle of a frame: the bootloader reads ahead of the frame that
        // started the application, and the network delivers whole frames.
        host_board_reset(&robot->board);
        host_robot_start_application(robot);
        busy = true;
    }
    if (host_board_take_reset(&robot->board)) {
        host_robot_reset(robot);
        busy = true;
    }
    // Received bytes wait: the chip would be reading them now.
    return busy || robot->board.receive_count != 0;
}
