// The host target: the simulated e-puck of boards/epuck_host, inside host
// programs and tests. Every size and switch of the host build; every host
// build names this file as TARGET_CONFIG (the top-level Makefile). The host
// tools describe "our e-puck" by it (the compiler's built-in target).

#ifndef EPUCK_HOST_CONFIG_H
#define EPUCK_HOST_CONFIG_H

// The simulated chip's flash is the e-puck's: its geometry and how this
// project divides it (the store, the bootloaders, the application).
#include "robots/epuck/epuck_flash_layout.h"

// --- the robot and the node's memory ------------------------------------------------
// The robot package the firmware runs (firmware/firmware.h).
#define ROBOT_HEADER "robots/epuck/epuck_robot.h"
// The VM's memories, as the node describes them to hosts: bytecode, stack,
// and the variable words after the robot's named ones (user variables and
// temporaries).
#define FIRMWARE_BYTECODE_WORDS      1024
#define FIRMWARE_STACK_WORDS         32
#define FIRMWARE_FREE_VARIABLE_WORDS 256
// The settings record (store/bytecode_store.h): the node id, then words
// for calibration (as on the robot).
#define STORE_SETTINGS_WORDS 44u

// --- the portable layers' switches (vm/vm_config.h, vm/node_config.h) -------------
// Threaded dispatch, the faster one with gcc and clang (docs/benchmarks.md);
// the tests build the switch too (tests/vm/vm_switch.c).
#ifndef VM_USE_COMPUTED_GOTO
#define VM_USE_COMPUTED_GOTO 1
#endif
#define VM_MAX_NATIVE_ARGUMENTS    16   // stack words of the widest native
#define NODE_INTER_BYTE_TIMEOUT_MS 500  // as GCtronic's e-puck firmware
#define NODE_STEP_BUDGET           1000 // as upstream's microcontroller glue
#define NODE_TRANSMIT_CHUNK        32   // one piece of a frame on its way out
// The whole description at once: the network never makes sending wait,
// and hosts (asebamassloader) expect a node's description in one piece.
#define NODE_DESCRIPTION_FRAMES_PER_POLL 0xFFFF

// Simulated time counts the e-puck's instruction cycles, so that timers and
// ADC scans fall at the robot's cycles: 7.3728 MHz × 8 (PLL) / 4 (hardware
// §1.6).
#define HOST_CYCLES_PER_SECOND 14745600ul

// The link. The host board takes what the simulated network delivers a
// whole frame at a time and refuses what does not fit, so its receive ring
// loses nothing whatever its size (two frames); it hands what is sent to
// its output at once, so its transmit ring (the robot's size) never fills.
#define HAL_LINK_RECEIVE_CAPACITY  1024u
#define HAL_LINK_TRANSMIT_CAPACITY 32u

// The simulated data EEPROM, kept in the memory file beside the flash.
#define HOST_EEPROM_WORDS 2048u

#endif
