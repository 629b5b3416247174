// The STM32F4 target on QEMU's netduinoplus2 board (an STM32F405, Debian's
// qemu-system-arm 7.2): every size and switch of the `make stm32f4` image.
// What the emulator does not model decides the board's switches
// (research/qemu-stm32.md): its RCC never reports a clock ready, its USART
// never raises the transmit-empty interrupt, its flash cannot be written.
// A real e-puck2 board would be a configuration header beside this one.

#ifndef NETDUINOPLUS2_CONFIG_H
#define NETDUINOPLUS2_CONFIG_H

#include "ports/stm32f4/stm32f4_flash_geometry.h"

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
// for calibration (the e-puck's count).
#define STORE_SETTINGS_WORDS 44u

// --- the portable layers' switches (vm/vm_config.h, vm/node_config.h) -------------
// GCC's labels as values: threaded dispatch.
#ifndef VM_USE_COMPUTED_GOTO
#define VM_USE_COMPUTED_GOTO 1
#endif
#define VM_MAX_NATIVE_ARGUMENTS    16   // stack words of the widest native
#define NODE_INTER_BYTE_TIMEOUT_MS 500  // as GCtronic's e-puck firmware
#define NODE_STEP_BUDGET           1000 // as upstream's microcontroller glue
#define NODE_TRANSMIT_CHUNK        32   // one piece of a frame on its way out
// The whole description at once: the transmit ring holds all of it.
#define NODE_DESCRIPTION_FRAMES_PER_POLL 0xFFFF

// --- clock -------------------------------------------------------------------------
// The core clock SysTick counts: QEMU's STM32F405 model runs its CPU clock at
// 168 MHz, what a real board reaches with its PLL.
#define STM32F4_CPU_HZ 168000000ul
// 0: keep the reset clock, do not start the crystal and the PLL (QEMU's RCC
// never says they are ready). A real board gives its crystal's frequency.
#define STM32F4_HSE_HZ 0ul

// --- the link: USART1, QEMU's first serial port ----------------------------------------
#define STM32F4_LINK_BAUD          115200ul
#define HAL_LINK_RECEIVE_CAPACITY  1024u // about two 522-byte frames: RAM is plenty
#define HAL_LINK_TRANSMIT_CAPACITY 4096u // the whole description at once: RAM is plenty
// 0: send by polling TXE (QEMU sends each byte at once and never raises the
// transmit interrupt); 1: from the transmit-empty interrupt (a real chip).
#define STM32F4_TRANSMIT_BY_INTERRUPT 0

// --- interrupt priorities (0 highest, 15 lowest; the top 4 bits of a byte) -----------
#define STM32F4_PRIORITY_USART1  4u
#define STM32F4_PRIORITY_SYSTICK 8u

// --- storage: the flash cannot be written under QEMU, so the bytecode store
// lives in RAM kept across resets (stm32f4_ram_flash.c), in four units of
// 4 KiB at the addresses of the real chip's sectors 1 to 4, which the linker
// script keeps free of code (linker/stm32f4-app.ld).
#define STM32F4_RAM_FLASH_BASE     0x08004000ul
#define STM32F4_RAM_FLASH_UNIT     0x1000ul
#define STM32F4_RAM_FLASH_UNITS    4u
#define STORE_BYTECODE_SLOT_BLOCKS 32u // a whole unit: 32 blocks of 128 bytes
#define STORE_SETTINGS_SLOT_BLOCKS 32u
#define STORE_BYTECODE_SLOT_0      STM32F4_RAM_FLASH_BASE
#define STORE_BYTECODE_SLOT_1      (STM32F4_RAM_FLASH_BASE + 1u * STM32F4_RAM_FLASH_UNIT)
#define STORE_SETTINGS_SLOT_0      (STM32F4_RAM_FLASH_BASE + 2u * STM32F4_RAM_FLASH_UNIT)
#define STORE_SETTINGS_SLOT_1      (STM32F4_RAM_FLASH_BASE + 3u * STM32F4_RAM_FLASH_UNIT)

// --- the robot's devices: none; hosts write the sensor variables ---------------
#define STM32F4_DEVICES_HEADER "boards/netduinoplus2/fed_robot.h"

#endif
