# The dsPIC30F6014A build of the e-puck images, with Microchip XC16:
#
#   make dspic30                 (or: make TARGET=dspic30)
#   make dspic30 XC16_DIR=/opt/microchip/xc16/v2.10/bin
#
# links two programs with XC16 and combines them with the host tool
# epuck-image (tools/flash), in build/dspic30/:
#
#   epuck-aseba-application.elf/.hex/.map  the VM, natives, firmware, the
#       e-puck's devices and this port, from dspic30_application_main.c,
#       linked with linker/epuck-app.gld
#   epuck-aseba-bootloader.elf/.hex/.map   the bootloader core (bootloader/)
#       from dspic30_bootloader_main.c, with the port's clock, pins, UART and
#       flash, linked with linker/epuck-bootloader.gld
#   epuck-aseba.hex          the application and its descriptor: what
#                            `asebacmd whex` or the console's flash sends
#   epuck-aseba-factory.hex  bootloader + application + descriptor: the first
#                            installation (factory Tiny Bootloader, programmer)
#
# Every file is compiled with the target's one configuration header,
# dspic30_config.h. `make dspic30-check` compiles every hal/dspic30 file but
# the DSP kernel with avr-gcc (16-bit int) against the simulated register
# header, and runs as part of `make cross-check`.

# XC16's bin folder: the newest installed version unless given.
XC16_DIR ?= $(or $(lastword $(sort $(wildcard /opt/microchip/xc16/v*/bin))),/opt/microchip/xc16/v2.10/bin)
XC16_GCC := $(XC16_DIR)/xc16-gcc
XC16_BIN2HEX := $(XC16_DIR)/xc16-bin2hex

DSPIC30_OUT := $(BUILD)/dspic30
DSPIC30_TARGET_CONFIG := '-DTARGET_CONFIG="hal/dspic30/dspic30_config.h"'
# The port's DSP-engine kernel (dspic30_dsp_kernel.c) replaces the portable
# native_functions/nat_dsp_kernel.c (same function); each image has its own
# entry point.
DSPIC30_APPLICATION_SOURCES := $(filter-out native_functions/nat_dsp_kernel.c \
                                            hal/dspic30/dspic30_bootloader_main.c, \
                     $(sort $(wildcard vm/*.c native_functions/*.c firmware/*.c hal/dspic30/*.c \
                                       drivers/epuck/*.c) bootloader/bytecode_store.c \
                            hal/hal_link_rings.c))
# The bootloader image: what dspic30_bootloader_main.c reaches. Unused
# functions are dropped at link time (-ffunction-sections, --gc-sections).
DSPIC30_BOOTLOADER_SOURCES := $(sort $(wildcard bootloader/*.c) hal/dspic30/dspic30_bootloader_main.c \
                                hal/dspic30/dspic30_clock.c hal/dspic30/dspic30_gpio.c \
                                hal/dspic30/dspic30_uart.c hal/dspic30/dspic30_nvm.c \
                                hal/hal_link_rings.c drivers/epuck/epuck_selector.c \
                                vm/node_crc.c)
DSPIC30_APPLICATION_OBJECTS := $(patsubst %.c,$(DSPIC30_OUT)/obj/%.o,$(DSPIC30_APPLICATION_SOURCES))
DSPIC30_BOOTLOADER_OBJECTS := $(patsubst %.c,$(DSPIC30_OUT)/obj/%.o,$(DSPIC30_BOOTLOADER_SOURCES))
DSPIC30_APPLICATION_SCRIPT := linker/epuck-app.gld
DSPIC30_BOOTLOADER_SCRIPT := linker/epuck-bootloader.gld
# -mcpu names the part; -omf=elf the object format bin2hex reads; one section
# per function lets the bootloader's link keep only what it calls.
DSPIC30_CFLAGS := -mcpu=30F6014A -omf=elf -std=gnu99 -Os -Wall -Wextra -I. -Ivm -Inative_functions \
                  -ffunction-sections $(DSPIC30_TARGET_CONFIG)
DSPIC30_LDFLAGS = -mcpu=30F6014A -omf=elf \
                  -Wl,--script=$(1),-Map=$(2:.elf=.map),--report-mem$(3)
# The bootloader's code is above PC 0xFFFF and has no room for a handle
# table below it (fact sheet §5.2): it takes no function pointers.
DSPIC30_BOOTLOADER_LDFLAGS := ,--gc-sections,--no-handles
EPUCK_IMAGE_TOOL := $(BUILD)/host/bin/epuck-image

ifeq ($(TARGET),dspic30)
.DEFAULT_GOAL := dspic30
endif

.PHONY: dspic30 dspic30-toolchain dspic30-check
dspic30: $(DSPIC30_OUT)/epuck-aseba.hex $(DSPIC30_OUT)/epuck-aseba-factory.hex

dspic30-toolchain:
	@test -x $(XC16_GCC) || { echo "dspic30: xc16-gcc not found in $(XC16_DIR): install Microchip MPLAB XC16 (microchip.com/xc16) or set XC16_DIR to its bin folder"; exit 1; }

$(DSPIC30_OUT)/obj/%.o: %.c | dspic30-toolchain
	@mkdir -p $(@D)
	$(XC16_GCC) $(DSPIC30_CFLAGS) -MMD -MP -c $< -o $@

$(DSPIC30_OUT)/epuck-aseba-application.elf: $(DSPIC30_APPLICATION_OBJECTS) \
                                            $(DSPIC30_APPLICATION_SCRIPT) | dspic30-toolchain
	$(XC16_GCC) $(call DSPIC30_LDFLAGS,$(DSPIC30_APPLICATION_SCRIPT),$@) \
	    $(DSPIC30_APPLICATION_OBJECTS) -o $@

$(DSPIC30_OUT)/epuck-aseba-bootloader.elf: $(DSPIC30_BOOTLOADER_OBJECTS) \
                                           $(DSPIC30_BOOTLOADER_SCRIPT) | dspic30-toolchain
	$(XC16_GCC) $(call DSPIC30_LDFLAGS,$(DSPIC30_BOOTLOADER_SCRIPT),$@,$(DSPIC30_BOOTLOADER_LDFLAGS)) \
	    $(DSPIC30_BOOTLOADER_OBJECTS) -o $@

# bin2hex writes the .hex next to the .elf.
$(DSPIC30_OUT)/%.hex: $(DSPIC30_OUT)/%.elf | dspic30-toolchain
	$(XC16_BIN2HEX) $< -omf=elf

# The descriptor, the checks of the bootloader image, and the merge.
$(DSPIC30_OUT)/epuck-aseba.hex $(DSPIC30_OUT)/epuck-aseba-factory.hex &: \
  $(DSPIC30_OUT)/epuck-aseba-application.hex $(DSPIC30_OUT)/epuck-aseba-bootloader.hex \
  $(EPUCK_IMAGE_TOOL) | dspic30-toolchain
	$(EPUCK_IMAGE_TOOL) $(DSPIC30_OUT)/epuck-aseba-application.hex \
	    $(DSPIC30_OUT)/epuck-aseba-bootloader.hex \
	    $(DSPIC30_OUT)/epuck-aseba.hex $(DSPIC30_OUT)/epuck-aseba-factory.hex

-include $(DSPIC30_APPLICATION_OBJECTS:.o=.d) $(DSPIC30_BOOTLOADER_OBJECTS:.o=.d)

# Every hal/dspic30 file compiled where int is 16 bits, warnings as errors;
# the DSP kernel needs XC16's DSP builtins (its host test runs it against a
# model of them).
DSPIC30_CHECK_SOURCES := $(filter-out hal/dspic30/dspic30_dsp_kernel.c,$(wildcard hal/dspic30/*.c)) \
                         hal/hal_link_rings.c
DSPIC30_CHECK_FLAGS := -std=gnu99 -Os -ffreestanding -Wall -Wextra -Werror -Wshadow -Wundef \
                       -Wpointer-arith -mmcu=atmega1284p -I. -Ivm -Inative_functions \
                       -DDSPIC30_SIMULATED_REGISTERS $(DSPIC30_TARGET_CONFIG)
dspic30-check: | $(DEPS_STAMP)
	@mkdir -p $(BUILD)/cross-dspic30
	@for source in $(DSPIC30_CHECK_SOURCES); do \
	    avr-gcc $(DSPIC30_CHECK_FLAGS) -c $$source \
	        -o $(BUILD)/cross-dspic30/$$(basename $${source%.c}).o || exit 1; \
	done
	@echo "== hal/dspic30 and its rings: $(words $(DSPIC30_CHECK_SOURCES)) files build with avr-gcc against the simulated registers"

cross-check: dspic30-check
