// The sizes of the parts of the e-puck firmware's RAM, as avr-gcc (16-bit
// int) lays them out: each array below is as long as the part it names, so
// that `avr-nm -S` on this object reads them (scripts/bench.sh). Nothing
// here is linked into an image.

#include "firmware/epuck_firmware.h"
#include "drivers/epuck/epuck_devices.h"
#include "hal/dspic30/dspic30_board.h"

const char ram_part_vm_bytecode[EPUCK_BYTECODE_WORDS * sizeof(uint16_t)];
const char ram_part_vm_variables[EPUCK_VARIABLES_WORDS * sizeof(int16_t)];
const char ram_part_vm_stack[EPUCK_STACK_WORDS * sizeof(int16_t)];
const char ram_part_vm_state[sizeof(vm_state)];
const char ram_part_node_state[sizeof(node_state)];
const char ram_part_node_receive_frame[sizeof(((node_state *)0)->frame)];
const char ram_part_firmware[sizeof(epuck_firmware)];
const char ram_part_board[sizeof(hal_board)];
const char ram_part_robot_devices[sizeof(epuck_robot)];
