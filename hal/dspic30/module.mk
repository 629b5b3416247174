# The dsPIC30F6014A build of the e-puck firmware image, with Microchip XC16:
#
#   make dspic30                 (or: make TARGET=dspic30)
#   make dspic30 XC16_DIR=/opt/microchip/xc16/v2.10/bin
#
# gives build/dspic30/epuck-aseba.hex (and .elf, .map). It compiles the VM,
# the natives, the firmware, this HAL and the e-puck drivers with the
# linker script linker/epuck-app.gld. `make dspic30-check` compiles every
# hal/dspic30 file with avr-gcc (16-bit int) against the simulated register
# header, and runs as part of `make cross-check`.

# XC16's bin folder: the newest installed version unless given.
XC16_DIR ?= $(or $(lastword $(sort $(wildcard /opt/microchip/xc16/v*/bin))),/opt/microchip/xc16/v2.10/bin)
XC16_GCC := $(XC16_DIR)/xc16-gcc
XC16_BIN2HEX := $(XC16_DIR)/xc16-bin2hex

DSPIC30_OUT := $(BUILD)/dspic30
# native_functions/nat_dsp_dspic30.c, the DSP-engine inner loop of the DSP
# natives, replaces the portable nat_dsp_kernel.c (same function).
DSPIC30_SOURCES := $(filter-out native_functions/nat_dsp_kernel.c, \
                     $(sort $(wildcard vm/*.c native_functions/*.c firmware/*.c hal/dspic30/*.c \
                                       drivers/epuck/*.c) bootloader/bytecode_store.c))
DSPIC30_OBJECTS := $(patsubst %.c,$(DSPIC30_OUT)/obj/%.o,$(DSPIC30_SOURCES))
DSPIC30_LINKER_SCRIPT := linker/epuck-app.gld
# -mcpu names the part; -omf=elf the object format bin2hex reads; the
# firmware's sizes reach the VM through VM_TARGET_CONFIG.
DSPIC30_CFLAGS := -mcpu=30F6014A -omf=elf -std=gnu99 -Os -Wall -Wextra -I. -Ivm -Inative_functions \
                  '-DVM_TARGET_CONFIG="firmware/epuck_config.h"'
DSPIC30_LDFLAGS := -mcpu=30F6014A -omf=elf \
                   -Wl,--script=$(DSPIC30_LINKER_SCRIPT),-Map=$(DSPIC30_OUT)/epuck-aseba.map,--report-mem

ifeq ($(TARGET),dspic30)
.DEFAULT_GOAL := dspic30
endif

.PHONY: dspic30 dspic30-toolchain dspic30-check
dspic30: $(DSPIC30_OUT)/epuck-aseba.hex

dspic30-toolchain:
	@test -x $(XC16_GCC) || { echo "dspic30: xc16-gcc not found in $(XC16_DIR): install Microchip MPLAB XC16 (microchip.com/xc16) or set XC16_DIR to its bin folder"; exit 1; }

$(DSPIC30_OUT)/obj/%.o: %.c | dspic30-toolchain
	@mkdir -p $(@D)
	$(XC16_GCC) $(DSPIC30_CFLAGS) -MMD -MP -c $< -o $@

$(DSPIC30_OUT)/epuck-aseba.elf: $(DSPIC30_OBJECTS) $(DSPIC30_LINKER_SCRIPT) | dspic30-toolchain
	$(XC16_GCC) $(DSPIC30_LDFLAGS) $(DSPIC30_OBJECTS) -o $@

# bin2hex writes the .hex next to the .elf.
$(DSPIC30_OUT)/epuck-aseba.hex: $(DSPIC30_OUT)/epuck-aseba.elf
	$(XC16_BIN2HEX) $< -omf=elf

-include $(DSPIC30_OBJECTS:.o=.d)

# Every hal/dspic30 file compiled where int is 16 bits, warnings as errors.
DSPIC30_CHECK_FLAGS := -std=gnu99 -Os -ffreestanding -Wall -Wextra -Werror -Wshadow -Wundef \
                       -Wpointer-arith -mmcu=atmega1284p -I. -Ivm -Inative_functions \
                       -DDSPIC30_SIMULATED_REGISTERS
dspic30-check: | $(DEPS_STAMP)
	@mkdir -p $(BUILD)/cross-dspic30
	@for source in $(wildcard hal/dspic30/*.c); do \
	    avr-gcc $(DSPIC30_CHECK_FLAGS) -c $$source \
	        -o $(BUILD)/cross-dspic30/$$(basename $${source%.c}).o || exit 1; \
	done
	@echo "== hal/dspic30: $(words $(wildcard hal/dspic30/*.c)) files build with avr-gcc against the simulated registers"

cross-check: dspic30-check
