// The host target: the simulated e-puck of hal/host, inside host programs
// and tests. Every size and switch of the host build; every host build names
// this file as TARGET_CONFIG (the top-level Makefile).

#ifndef HOST_CONFIG_H
#define HOST_CONFIG_H

// The simulated chip's flash is the e-puck's: its geometry and how this
// project divides it (the store, the bootloaders, the application).
#include "hal/dspic30/dspic30_flash_layout.h"

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
