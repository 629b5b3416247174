# The dsPIC30F6014A build of the e-puck images:
#
#   make dspic30                             (or: make TARGET=dspic30)
#   make dspic30 DSPIC_TOOLCHAIN=DIR         a pic30-elf GCC toolchain (DIR or DIR/bin
#                                            holds pic30-elf-gcc)
#   make dspic30 XC16_DIR=/opt/microchip/xc16/v2.10/bin    Microchip MPLAB XC16
#
# Either toolchain builds the same images from the same sources and flags:
# the port brings its own start-up (dspic30_reset.s, dspic30_startup.c), run-time helpers
# (dspic30_runtime.c), register names (linker/dspic30f6014a-registers.gld) and
# linker scripts, and links with -nostartfiles -nostdlib, so nothing of
# Microchip's non-GPL libraries is used even with XC16. Without
# DSPIC_TOOLCHAIN or XC16_DIR, an installed XC16 (/opt/microchip/xc16/v*) is
# used, else the GPL build of XC16's compiler that `scripts/install-deps.sh
# dspic30` unpacks into $(BUILD)/toolchains from ../shared/toolchains/pic30.
#
# In build/dspic30/:
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
# and scripts/check-dspic30-images.py checks them before they are kept.
#
# Every file is compiled with the target's one configuration header,
# boards/epuck_dspic30/epuck_dspic30_config.h. `make dspic30-check` compiles
# every file of the port and of the board but the DSP kernel with avr-gcc
# (16-bit int) against the simulated register header, and runs as part of
# `make cross-check`.

# --- the toolchain: the only place where XC16 and pic30-elf differ ----------
DSPIC_GPL_TOOLCHAIN := $(BUILD)/toolchains/pic30-elf
XC16_FOUND := $(patsubst %/xc16-gcc,%,$(lastword $(sort $(wildcard /opt/microchip/xc16/v*/bin/xc16-gcc))))
ifneq ($(DSPIC_TOOLCHAIN),)
# DIR, DIR/bin, or the compiler itself (named so that a wrong one is said).
DSPIC_PREFIX := $(if $(filter %gcc,$(DSPIC_TOOLCHAIN)),$(patsubst %gcc,%,$(DSPIC_TOOLCHAIN)),$(if \
                  $(wildcard $(DSPIC_TOOLCHAIN)/bin/pic30-elf-gcc),$(DSPIC_TOOLCHAIN)/bin,$(DSPIC_TOOLCHAIN))/pic30-elf-)
DSPIC_TOOLCHAIN_NAME := DSPIC_TOOLCHAIN=$(DSPIC_TOOLCHAIN)
else ifneq ($(or $(XC16_DIR),$(XC16_FOUND)),)
XC16_DIR ?= $(XC16_FOUND)
DSPIC_PREFIX := $(XC16_DIR)/xc16-
DSPIC_TOOLCHAIN_NAME := Microchip XC16 in $(XC16_DIR)
# XC16's programs take the object format as an option; the GPL driver does
# not know it (it would read -omf=elf as "-o mf=elf").
DSPIC_OMF := -omf=elf
else
DSPIC_PREFIX := $(DSPIC_GPL_TOOLCHAIN)/bin/pic30-elf-
DSPIC_TOOLCHAIN_NAME := the GPL pic30-elf toolchain in $(DSPIC_GPL_TOOLCHAIN)
DSPIC_TOOLCHAIN_STAMP := $(BUILD)/.deps-dspic30
endif
DSPIC_GCC := $(DSPIC_PREFIX)gcc
DSPIC_BIN2HEX := $(DSPIC_PREFIX)bin2hex
DSPIC_OBJDUMP := $(DSPIC_PREFIX)objdump
DSPIC_NM := $(DSPIC_PREFIX)nm

DSPIC30_OUT := $(BUILD)/dspic30
DSPIC30_TARGET_CONFIG := '-DTARGET_CONFIG="boards/epuck_dspic30/epuck_dspic30_config.h"'
# The application: the portable layers, the e-puck's package, its board on
# this chip, and the port. The port's DSP-engine kernel (dspic30_dsp_kernel.c)
# replaces the portable native_functions/nat_dsp_kernel.c (same function);
# each image has its own entry point.
DSPIC30_APPLICATION_SOURCES := $(filter-out native_functions/nat_dsp_kernel.c \
                                            ports/dspic30/dspic30_bootloader_main.c, \
                     $(sort $(wildcard vm/*.c native_functions/*.c firmware/*.c \
                                       robots/epuck/*.c robots/epuck/devices/*.c \
                                       boards/epuck_dspic30/*.c ports/dspic30/*.c) \
                            store/bytecode_store.c hal/hal_link_rings.c)) ports/dspic30/dspic30_reset.s
# The bootloader image: what dspic30_bootloader_main.c reaches. Unused
# functions are dropped at link time (-ffunction-sections, --gc-sections).
DSPIC30_BOOTLOADER_SOURCES := $(sort $(wildcard bootloader/*.c) store/bytecode_store.c \
                                ports/dspic30/dspic30_bootloader_main.c \
                                ports/dspic30/dspic30_clock.c boards/epuck_dspic30/dspic30_gpio.c \
                                ports/dspic30/dspic30_uart.c ports/dspic30/dspic30_nvm.c \
                                ports/dspic30/dspic30_startup.c ports/dspic30/dspic30_runtime.c \
                                hal/hal_link_rings.c robots/epuck/devices/epuck_selector.c \
                                vm/node_crc.c) ports/dspic30/dspic30_reset.s
DSPIC30_APPLICATION_OBJECTS := $(patsubst %,$(DSPIC30_OUT)/obj/%.o,$(basename $(DSPIC30_APPLICATION_SOURCES)))
DSPIC30_BOOTLOADER_OBJECTS := $(patsubst %,$(DSPIC30_OUT)/obj/%.o,$(basename $(DSPIC30_BOOTLOADER_SOURCES)))
DSPIC30_APPLICATION_SCRIPT := linker/epuck-app.gld
DSPIC30_BOOTLOADER_SCRIPT := linker/epuck-bootloader.gld
DSPIC30_SCRIPTS_INCLUDED := linker/dspic30f6014a-registers.gld
# -mcpu names the part; -ffreestanding: there is
# no C library (<stdint.h> is the compiler's own); one section per function
# lets the bootloader's link keep only what it calls.
DSPIC30_CFLAGS := -mcpu=30F6014A $(DSPIC_OMF) -std=gnu99 -Os -ffreestanding -Wall -Wextra -Werror \
                  -I. -Ivm -Inative_functions -ffunction-sections $(DSPIC30_TARGET_CONFIG)
# No start files nor libraries: the port's own start-up and helpers. The
# linker scripts lay out the reset vector and the vector tables themselves
# (--no-isr, --no-ivt); --no-pack-data keeps .dinit in the format that
# dspic30_startup.c reads; --fatal-warnings: a region overflow or an
# allocator's guess is an error.
DSPIC30_LDFLAGS = -mcpu=30F6014A $(DSPIC_OMF) -nostartfiles -nostdlib \
                  -Wl,--script=$(1),-Map=$(2:.elf=.map),--report-mem,--no-pack-data,--no-isr,--no-ivt$(3)
# The bootloader's code is above PC 0xFFFF and has no room for a handle
# table below it (fact sheet §5.2): it takes no function pointers.
DSPIC30_BOOTLOADER_LDFLAGS := ,--gc-sections,--no-handles
# The application keeps only what its entry point, its vectors and its
# descriptor reach (the linker script KEEPs those): the host-only parts of
# the portable layers (a node's helpers the e-puck never calls) drop out,
# 410 instruction words.
DSPIC30_APPLICATION_LDFLAGS := ,--gc-sections
EPUCK_IMAGE_TOOL := $(BUILD)/host/bin/epuck-image

ifeq ($(TARGET),dspic30)
.DEFAULT_GOAL := dspic30
endif

.PHONY: dspic30 dspic30-toolchain dspic30-check
dspic30: $(DSPIC30_OUT)/epuck-aseba.hex $(DSPIC30_OUT)/epuck-aseba-factory.hex

# A dsPIC toolchain, or both ways of getting one; a compiler for another
# machine is named as such.
dspic30-toolchain: | $(DSPIC_TOOLCHAIN_STAMP)
	@test -x $(DSPIC_GCC) || { \
	    echo "dspic30: no dsPIC compiler: $(DSPIC_GCC) not found ($(DSPIC_TOOLCHAIN_NAME))." >&2; \
	    echo "  Either install Microchip MPLAB XC16 (https://www.microchip.com/xc16) and give XC16_DIR=ITS/bin," >&2; \
	    echo "  or give DSPIC_TOOLCHAIN=DIR, a pic30-elf GCC toolchain built from XC16's GPL sources" >&2; \
	    echo "  (scripts/install-deps.sh dspic30 unpacks the project's into $(DSPIC_GPL_TOOLCHAIN))." >&2; \
	    exit 1; }
	@machine=$$($(DSPIC_GCC) -dumpmachine 2>/dev/null); case "$$machine" in pic30*|*xc16*) ;; *) \
	    $(DSPIC_GCC) --version 2>/dev/null | grep -qi 'xc16' || { \
	    echo "dspic30: $(DSPIC_GCC) compiles for '$$machine', not for the dsPIC30 (pic30): $(DSPIC_TOOLCHAIN_NAME) is not a dsPIC toolchain" >&2; \
	    exit 1; };; esac

$(DSPIC30_OUT)/obj/%.o: %.c | dspic30-toolchain
	@mkdir -p $(@D)
	$(DSPIC_GCC) $(DSPIC30_CFLAGS) -MMD -MP -c $< -o $@

$(DSPIC30_OUT)/obj/%.o: %.s | dspic30-toolchain
	@mkdir -p $(@D)
	$(DSPIC_GCC) -mcpu=30F6014A $(DSPIC_OMF) -c $< -o $@

$(DSPIC30_OUT)/epuck-aseba-application.elf: $(DSPIC30_APPLICATION_OBJECTS) \
                                            $(DSPIC30_APPLICATION_SCRIPT) $(DSPIC30_SCRIPTS_INCLUDED) | dspic30-toolchain
	$(DSPIC_GCC) $(call DSPIC30_LDFLAGS,$(DSPIC30_APPLICATION_SCRIPT),$@,$(DSPIC30_APPLICATION_LDFLAGS)) \
	    $(DSPIC30_APPLICATION_OBJECTS) -o $@ > $(@:.elf=.memory) || \
	  scripts/check-dspic30-images.py --overflow $(DSPIC_PREFIX) $(DSPIC30_APPLICATION_SCRIPT) \
	    program $(DSPIC30_APPLICATION_OBJECTS)

$(DSPIC30_OUT)/epuck-aseba-bootloader.elf: $(DSPIC30_BOOTLOADER_OBJECTS) \
                                           $(DSPIC30_BOOTLOADER_SCRIPT) $(DSPIC30_SCRIPTS_INCLUDED) | dspic30-toolchain
	$(DSPIC_GCC) $(call DSPIC30_LDFLAGS,$(DSPIC30_BOOTLOADER_SCRIPT),$@,$(DSPIC30_BOOTLOADER_LDFLAGS)) \
	    $(DSPIC30_BOOTLOADER_OBJECTS) -o $@ > $(@:.elf=.memory) || \
	  scripts/check-dspic30-images.py --overflow $(DSPIC_PREFIX) $(DSPIC30_BOOTLOADER_SCRIPT) \
	    program $(DSPIC30_BOOTLOADER_OBJECTS)

# bin2hex writes the .hex next to the .elf.
$(DSPIC30_OUT)/%.hex: $(DSPIC30_OUT)/%.elf | dspic30-toolchain
	$(DSPIC_BIN2HEX) $< $(DSPIC_OMF)

# The descriptor, the checks of the bootloader image, and the merge; then
# the images against their linked programs (scripts/check-dspic30-images.py).
$(DSPIC30_OUT)/epuck-aseba.hex $(DSPIC30_OUT)/epuck-aseba-factory.hex &: \
  $(DSPIC30_OUT)/epuck-aseba-application.hex $(DSPIC30_OUT)/epuck-aseba-bootloader.hex \
  $(EPUCK_IMAGE_TOOL) scripts/check-dspic30-images.py | dspic30-toolchain
	$(EPUCK_IMAGE_TOOL) $(DSPIC30_OUT)/epuck-aseba-application.hex \
	    $(DSPIC30_OUT)/epuck-aseba-bootloader.hex \
	    $(DSPIC30_OUT)/epuck-aseba.hex $(DSPIC30_OUT)/epuck-aseba-factory.hex
	scripts/check-dspic30-images.py $(DSPIC_PREFIX) $(DSPIC30_OUT) $(EPUCK_IMAGE_TOOL) || \
	    { rm -f $(DSPIC30_OUT)/epuck-aseba.hex $(DSPIC30_OUT)/epuck-aseba-factory.hex; exit 1; }

-include $(DSPIC30_APPLICATION_OBJECTS:.o=.d) $(DSPIC30_BOOTLOADER_OBJECTS:.o=.d)

# Every file of the port and of the e-puck's board on it compiled where int
# is 16 bits, warnings as errors; not the two that are dsPIC assembly at
# heart: the DSP kernel (its host test runs it against a model of the
# engine) and the camera's timed row read (the arena's dsPIC robots run it).
DSPIC30_ASSEMBLY_SOURCES := ports/dspic30/dspic30_dsp_kernel.c boards/epuck_dspic30/dspic30_camera_row.c
DSPIC30_CHECK_SOURCES := $(filter-out $(DSPIC30_ASSEMBLY_SOURCES),$(wildcard ports/dspic30/*.c) \
                         $(wildcard boards/epuck_dspic30/*.c)) hal/hal_link_rings.c
DSPIC30_CHECK_FLAGS := -std=gnu99 -Os -ffreestanding -Wall -Wextra -Werror -Wshadow -Wundef \
                       -Wpointer-arith -mmcu=atmega1284p -I. -Ivm -Inative_functions \
                       -DDSPIC30_SIMULATED_REGISTERS $(DSPIC30_TARGET_CONFIG)
dspic30-check: | $(DEPS_STAMP)
	@mkdir -p $(BUILD)/cross-dspic30
	@for source in $(DSPIC30_CHECK_SOURCES); do \
	    avr-gcc $(DSPIC30_CHECK_FLAGS) -c $$source \
	        -o $(BUILD)/cross-dspic30/$$(basename $${source%.c}).o || exit 1; \
	done
	@echo "== ports/dspic30, boards/epuck_dspic30 and the rings: $(words $(DSPIC30_CHECK_SOURCES)) files build with avr-gcc against the simulated registers"

cross-check: dspic30-check
