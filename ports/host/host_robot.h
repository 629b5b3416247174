// A simulated e-puck from power-on: the board, the Aseba bootloader and the
// firmware, with the chip's reset sequence. After a reset (the firmware's
// REBOOT, or the host's request) the bootloader runs first: it waits
// BOOT_WAIT_MS for a host, programs application rows, and starts the
// application when the descriptor in flash says a valid one is there. The
// host cannot execute dsPIC instructions, so "the application" is this
// build's firmware, started whenever the flashed image is valid; flashing
// therefore changes what the bootloader accepts, not the code that runs.
// The factory Tiny Bootloader's second in front of ours is not modelled.

#ifndef HOST_ROBOT_H
#define HOST_ROBOT_H

#include <stdbool.h>
#include <stdint.h>

#include "boards/epuck_host/host_board.h"
#include "bootloader/bootloader.h"
#include "firmware/firmware.h"
#include "robots/epuck/devices/epuck_devices.h"

typedef enum host_robot_mode {
    HOST_ROBOT_IN_BOOTLOADER,
    HOST_ROBOT_IN_APPLICATION
} host_robot_mode;

// host_robot_init's node id for a robot that decides at each start, as the
// chip does: the node id in its stored settings, else its selector's
// (store/bytecode_store.h, store_node_id).
#define HOST_ROBOT_NODE_ID_AT_BOOT 0u

typedef struct host_robot {
    hal_board board;
    uint16_t given_node_id; // host_robot_init's
    uint16_t node_id;       // the bootloader's and the firmware's since the last start
    host_robot_mode mode;
    uint32_t resets; // since power-on
    bootloader loader;
    firmware_state firmware;
    robot_devices devices; // the e-puck's, under the firmware
} host_robot;

// Prepares the board (flat world, link output to `link_output`, memories
// erased) without powering on: install an image and place the robot first.
// `node_id` is the id the robot answers to, or HOST_ROBOT_NODE_ID_AT_BOOT.
void host_robot_init(host_robot *robot,
                     uint16_t node_id,
                     void (*link_output)(void *context, const uint8_t *bytes, uint16_t count),
                     void *link_context);

// Powers the robot on, as the chip powers on: its bootloader decides. With a
// valid application in flash, the firmware starts at once (the bootloader's
// second of waiting for a host is not waited out: a simulator starts its
// robots together, before any tool is there); without one (an interrupted
// flashing), the robot stays in its bootloader, waiting for an image.
void host_robot_power_on(host_robot *robot);

// Starts the firmware, as the bootloader does when it jumps to a valid
// application.
void host_robot_start_application(host_robot *robot);

// Works out node_id again as a start would (after the world or the memories
// changed, before power-on).
void host_robot_update_node_id(host_robot *robot);

// Resets the chip: peripherals stop and the bootloader starts.
void host_robot_reset(host_robot *robot);

// One pass of whatever runs (bootloader or firmware), then the reset it
// asked for if any; returns whether more work is waiting.
bool host_robot_poll(host_robot *robot);

#endif
