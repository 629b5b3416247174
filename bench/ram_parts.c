// The sizes of the parts of the e-puck firmware's RAM, as avr-gcc (16-bit
// int) lays them out: each array below is as long as the part it names, so
// that `avr-nm -S` on this object reads them (scripts/bench.sh). Nothing
// here is linked into an image.

#include "firmware/firmware.h"
#include "robots/epuck/devices/epuck_devices.h"
#include "boards/epuck_dspic30/epuck_dspic30_board.h"

const char ram_part_vm_bytecode[FIRMWARE_BYTECODE_WORDS * sizeof(uint16_t)];
const char ram_part_vm_variables[FIRMWARE_VARIABLE_WORDS * sizeof(int16_t)];
const char ram_part_vm_stack[FIRMWARE_STACK_WORDS * sizeof(int16_t)];
const char ram_part_vm_state[sizeof(vm_state)];
const char ram_part_node_state[sizeof(node_state)];
const char ram_part_node_receive_frame[sizeof(((node_state *)0)->frame)];
const char ram_part_firmware[sizeof(firmware_state)];
const char ram_part_board[sizeof(hal_board)];
const char ram_part_robot_devices[sizeof(robot_devices)];
