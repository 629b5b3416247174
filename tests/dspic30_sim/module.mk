# Tests of the dsPIC30F simulator (tools/dspic30_sim), against independent
# oracles: Microchip's disassembler for the decoder and disassembler.
# The pic30-elf toolchain that tools/dspic30_sim/module.mk unpacks (this
# file is read before it).
PIC30_BIN ?= $(BUILD)/toolchains/pic30-elf/bin
PIC30_TOOLCHAIN ?= $(PIC30_BIN)/pic30-elf-gcc

DSPIC30_SIM_TEST_LDLIBS := -lgtest -lgtest_main -pthread

TESTS += dspic30_sim_disassembler_test
dspic30_sim_disassembler_test_SOURCES := tests/dspic30_sim/disassembler_test.cpp \
                                         tests/dspic30_sim/pic30_toolchain.cpp
dspic30_sim_disassembler_test_LIBS := dspic30_sim
dspic30_sim_disassembler_test_LDLIBS := $(DSPIC30_SIM_TEST_LDLIBS)
EXTRA_CFLAGS_tests/dspic30_sim/pic30_toolchain := '-DPIC30_BIN="$(PIC30_BIN)"'
$(BUILD)/host-sanitize/tests/dspic30_sim_disassembler_test \
$(BUILD)/host/tests/dspic30_sim_disassembler_test: | $(PIC30_TOOLCHAIN)

TESTS += dspic30_sim_semantics_test
dspic30_sim_semantics_test_SOURCES := tests/dspic30_sim/semantics_test.cpp \
                                      tests/dspic30_sim/pic30_toolchain.cpp
dspic30_sim_semantics_test_LIBS := dspic30_sim
dspic30_sim_semantics_test_LDLIBS := $(DSPIC30_SIM_TEST_LDLIBS)
$(BUILD)/host-sanitize/tests/dspic30_sim_semantics_test \
$(BUILD)/host/tests/dspic30_sim_semantics_test: | $(PIC30_TOOLCHAIN)

# --- the GCC torture corpus ----------------------------------------------------
# ../shared/vectors/gcc-torture: 818 C tests of GCC's execution suite, each
# built here into a HEX image at build time (make builds only what changed),
# on the port's own start-up and 32-bit helpers (ports/dspic30: what the
# e-puck's images run) and a whole-chip layout (tests/dspic30_sim/runtime).
# The toolchain's compiler does not search its own lib/gcc include folders
# (stddef.h, limits.h, ...): they are named here.
TORTURE_SOURCE := ../shared/vectors/gcc-torture
TORTURE_OUT := $(BUILD)/dspic30_sim/torture
TORTURE_RUNTIME := tests/dspic30_sim/runtime
TORTURE_SCRIPT := $(TORTURE_RUNTIME)/bare_chip.gld
TORTURE_NAMES := $(sort $(notdir $(basename $(wildcard $(TORTURE_SOURCE)/tests/*.c))))
TORTURE_IMAGES := $(patsubst %,$(TORTURE_OUT)/%.hex,$(TORTURE_NAMES))
PIC30_GCC_INCLUDES = -isystem $(PIC30_BIN)/../lib/gcc/pic30-elf/4.5.1/include \
                     -isystem $(PIC30_BIN)/../lib/gcc/pic30-elf/4.5.1/include-fixed
PIC30_CFLAGS := -mcpu=30F6014A -Os
# The port's start-up, the first object of every link, and its helpers.
BARE_STARTUP := $(TORTURE_OUT)/support/dspic30_reset.o $(TORTURE_OUT)/support/dspic30_startup.o \
                $(TORTURE_OUT)/support/dspic30_runtime.o
TORTURE_SUPPORT := $(BARE_STARTUP) $(TORTURE_OUT)/support/uart_exit.o $(TORTURE_OUT)/support/libc.o
# Links a bare program: $(1) = output .elf, $(2) = objects (the start-up first).
define PIC30_LINK
$(PIC30_BIN)/pic30-elf-gcc -nostartfiles -nostdlib -T $(TORTURE_SCRIPT) $(2) \
    -Wl,--no-pack-data,--no-isr,--no-ivt -o $(1)
endef

$(TORTURE_OUT)/support/dspic30_reset.o: ports/dspic30/dspic30_reset.s | $(PIC30_TOOLCHAIN)
	@mkdir -p $(@D)
	$(PIC30_BIN)/pic30-elf-gcc -mcpu=30F6014A -c $< -o $@
$(TORTURE_OUT)/support/dspic30_%.o: ports/dspic30/dspic30_%.c ports/dspic30/dspic30_registers.h \
                                    ports/dspic30/dspic30_startup.h | $(PIC30_TOOLCHAIN)
	@mkdir -p $(@D)
	$(PIC30_BIN)/pic30-elf-gcc $(PIC30_CFLAGS) -std=gnu99 -ffreestanding -Wall -Wextra -Werror \
	    $(PIC30_GCC_INCLUDES) -c $< -o $@
$(TORTURE_OUT)/support/%.o: $(TORTURE_SOURCE)/support/%.c | $(PIC30_TOOLCHAIN)
	@mkdir -p $(@D)
	$(PIC30_BIN)/pic30-elf-gcc $(PIC30_CFLAGS) $(PIC30_GCC_INCLUDES) -c $< -o $@
# The tests compile without -mcpu, which makes the compiler read the whole
# device database (474 devices, about 0.15 s of each compile, 818 times);
# the assembler still takes the device (its division timing). The code is
# the same: the 818 assembly outputs of this toolchain with and without
# -mcpu differ only in two section names made of random numbers.
TORTURE_CFLAGS := -Os -Wa,-p30F6014A
$(TORTURE_OUT)/%.o: $(TORTURE_SOURCE)/tests/%.c | $(PIC30_TOOLCHAIN)
	@mkdir -p $(@D)
	@$(PIC30_BIN)/pic30-elf-gcc $(TORTURE_CFLAGS) -w $(PIC30_GCC_INCLUDES) \
	    -I$(TORTURE_SOURCE)/support/include -Dmain=torture_main -c $< -o $@
$(TORTURE_OUT)/%.hex: $(TORTURE_OUT)/%.o $(TORTURE_SUPPORT) $(TORTURE_SCRIPT) $(TORTURE_RUNTIME)/torture_p30f6014a.gld
	@$(call PIC30_LINK,$(@:.hex=.elf),$(TORTURE_SUPPORT) $<)
	@$(PIC30_BIN)/pic30-elf-bin2hex $(@:.hex=.elf)
.PRECIOUS: $(TORTURE_OUT)/%.o
# Kept, so that a later make does not rebuild them and relink every image.
.SECONDARY: $(TORTURE_SUPPORT)

TESTS += dspic30_sim_torture_test
dspic30_sim_torture_test_SOURCES := tests/dspic30_sim/torture_test.cpp
dspic30_sim_torture_test_LIBS := dspic30_sim
dspic30_sim_torture_test_LDLIBS := $(DSPIC30_SIM_TEST_LDLIBS)
EXTRA_CFLAGS_tests/dspic30_sim/torture_test := '-DTORTURE_MANIFEST="$(TORTURE_SOURCE)/manifest.tsv"' \
                                                '-DTORTURE_IMAGES="$(TORTURE_OUT)"'
$(BUILD)/host-sanitize/tests/dspic30_sim_torture_test \
$(BUILD)/host/tests/dspic30_sim_torture_test: | $(TORTURE_IMAGES)

# --- differential programs ---------------------------------------------------
# The C programs of tests/dspic30_sim/differential, for the dsPIC (with the
# bare programs' support above) and for the host (with UBSan).
DIFFERENTIAL_SOURCE := tests/dspic30_sim/differential
DIFFERENTIAL_OUT := $(BUILD)/dspic30_sim/differential
DIFFERENTIAL_PROGRAMS := arithmetic control constants
DIFFERENTIAL_OUTPUTS := $(foreach p,$(DIFFERENTIAL_PROGRAMS),$(DIFFERENTIAL_OUT)/$(p).hex $(DIFFERENTIAL_OUT)/$(p).host)
$(DIFFERENTIAL_OUT)/%.host: $(DIFFERENTIAL_SOURCE)/%.c $(DIFFERENTIAL_SOURCE)/harness_host.c \
                            $(DIFFERENTIAL_SOURCE)/harness.h
	@mkdir -p $(@D)
	$(CC) -std=gnu99 -O2 -Wall -Wextra -Werror -fsanitize=undefined -fno-sanitize-recover=all \
	    $< $(DIFFERENTIAL_SOURCE)/harness_host.c -o $@
$(DIFFERENTIAL_OUT)/%.o: $(DIFFERENTIAL_SOURCE)/%.c $(DIFFERENTIAL_SOURCE)/harness.h | $(PIC30_TOOLCHAIN)
	@mkdir -p $(@D)
	$(PIC30_BIN)/pic30-elf-gcc $(PIC30_CFLAGS) -std=gnu99 -ffreestanding -Wall -Wextra -Werror \
	    $(PIC30_GCC_INCLUDES) -c $< -o $@
$(DIFFERENTIAL_OUT)/%.hex: $(DIFFERENTIAL_OUT)/%.o $(DIFFERENTIAL_OUT)/harness_dspic30.o $(TORTURE_SUPPORT) \
                           $(TORTURE_SCRIPT)
	$(call PIC30_LINK,$(@:.hex=.elf),$(BARE_STARTUP) $< \
	    $(DIFFERENTIAL_OUT)/harness_dspic30.o $(TORTURE_OUT)/support/libc.o)
	$(PIC30_BIN)/pic30-elf-bin2hex $(@:.hex=.elf)
.PRECIOUS: $(DIFFERENTIAL_OUT)/%.o

TESTS += dspic30_sim_differential_test
dspic30_sim_differential_test_SOURCES := tests/dspic30_sim/differential_test.cpp \
                                         tests/dspic30_sim/pic30_toolchain.cpp
dspic30_sim_differential_test_LIBS := dspic30_sim
dspic30_sim_differential_test_LDLIBS := $(DSPIC30_SIM_TEST_LDLIBS)
EXTRA_CFLAGS_tests/dspic30_sim/differential_test := '-DDIFFERENTIAL_OUT="$(DIFFERENTIAL_OUT)"'
$(BUILD)/host-sanitize/tests/dspic30_sim_differential_test \
$(BUILD)/host/tests/dspic30_sim_differential_test: | $(DIFFERENTIAL_OUTPUTS)

TESTS += dspic30_sim_system_test
dspic30_sim_system_test_SOURCES := tests/dspic30_sim/system_test.cpp tests/dspic30_sim/pic30_toolchain.cpp
dspic30_sim_system_test_LIBS := dspic30_sim
dspic30_sim_system_test_LDLIBS := $(DSPIC30_SIM_TEST_LDLIBS)
$(BUILD)/host-sanitize/tests/dspic30_sim_system_test \
$(BUILD)/host/tests/dspic30_sim_system_test: | $(PIC30_TOOLCHAIN)

TESTS += dspic30_sim_program_test
dspic30_sim_program_test_SOURCES := tests/dspic30_sim/program_test.cpp tests/dspic30_sim/pic30_toolchain.cpp
dspic30_sim_program_test_LIBS := dspic30_sim
dspic30_sim_program_test_LDLIBS := $(DSPIC30_SIM_TEST_LDLIBS)
EXTRA_CFLAGS_tests/dspic30_sim/program_test := '-DDSPIC30_SIM="$(BUILD)/host-sanitize/bin/dspic30-sim"'
$(BUILD)/host-sanitize/tests/dspic30_sim_program_test \
$(BUILD)/host/tests/dspic30_sim_program_test: | $(PIC30_TOOLCHAIN) $(BUILD)/host-sanitize/bin/dspic30-sim

# The factory image that `make dspic30` links, run from reset on the
# simulator until it answers LIST_NODES (tests/dspic30_sim/factory_image_test.py,
# "N passed, N failed"): `make test` builds both first.
DSPIC30_FACTORY_TEST := $(BUILD)/host-sanitize/tests/dspic30_factory_image_test
TEST_SCRIPTS += $(DSPIC30_FACTORY_TEST)
$(DSPIC30_FACTORY_TEST): tests/dspic30_sim/factory_image_test.py $(BUILD)/host/bin/dspic30-sim \
                         $(DSPIC30_OUT)/epuck-aseba-factory.hex
	@mkdir -p $(@D)
	@printf '#!/usr/bin/env bash\n# Generated by tests/dspic30_sim/module.mk.\ncd "%s" && exec tests/dspic30_sim/factory_image_test.py "$$@"\n' \
	    "$(CURDIR)" > $@
	@chmod +x $@

# Deployment on the real machine code: the images of `make dspic30` on
# dspic30-sim with UART1 on a TCP port, flashed by the console and loaded by
# asebamassloader (deployment_test.py), and switched on again after power
# cuts at NVM operations of a flashing and of a program store
# (power_cut_test.py, in four parts of under a minute each).
DSPIC30_DEPLOYMENT_INPUTS := tests/dspic30_sim/sim_node.py $(BUILD)/host/bin/dspic30-sim \
                             $(BUILD)/host/bin/aseba $(DSPIC30_OUT)/epuck-aseba-factory.hex \
                             $(DSPIC30_OUT)/epuck-aseba.hex
DSPIC30_DEPLOYMENT_TESTS := $(BUILD)/host-sanitize/tests/dspic30_deployment_test \
                            $(foreach p,flash-same flash-new store-odd store-even,$(BUILD)/host-sanitize/tests/dspic30_power_cut_$(p)_test)
TEST_SCRIPTS += $(DSPIC30_DEPLOYMENT_TESTS)
# $(1): the script, $(2): its argument.
define DSPIC30_SCRIPT_WRAPPER
	@mkdir -p $(@D)
	@printf '#!/usr/bin/env bash\n# Generated by tests/dspic30_sim/module.mk.\ncd "%s" && exec tests/dspic30_sim/%s %s "$$@"\n' \
	    "$(CURDIR)" "$(1)" "$(2)" > $@
	@chmod +x $@
endef
$(BUILD)/host-sanitize/tests/dspic30_deployment_test: tests/dspic30_sim/deployment_test.py \
                                                      $(DSPIC30_DEPLOYMENT_INPUTS)
	$(call DSPIC30_SCRIPT_WRAPPER,deployment_test.py,)
$(BUILD)/host-sanitize/tests/dspic30_power_cut_%_test: tests/dspic30_sim/power_cut_test.py \
                                                      $(DSPIC30_DEPLOYMENT_INPUTS)
	$(call DSPIC30_SCRIPT_WRAPPER,power_cut_test.py,$*)

# The factory image as a robot of the arena (tools/emulator/dspic30_robot.hpp),
# checked against the host-built robot in the same world.
TESTS += dspic30_arena_robot_test
dspic30_arena_robot_test_SOURCES := tests/dspic30_sim/arena_robot_test.cpp
dspic30_arena_robot_test_LIBS := aseba_dspic30_robot dspic30_sim aseba_client aseba_arena \
                                 aseba_emulator_network aseba_host_robot aseba_flash aseba_firmware \
                                 aseba_epuck aseba_store aseba_bootloader aseba_host_board \
                                 aseba_compiler aseba_node aseba_vm aseba_natives
dspic30_arena_robot_test_LDLIBS := -lenki $(DSPIC30_SIM_TEST_LDLIBS)
EXTRA_CFLAGS_tests/dspic30_sim/arena_robot_test := \
    '-DDSPIC30_FACTORY_HEX="$(DSPIC30_OUT)/epuck-aseba-factory.hex"' \
    '-DDSPIC30_APPLICATION_MAP="$(DSPIC30_OUT)/epuck-aseba-application.map"'
$(BUILD)/host-sanitize/tests/dspic30_arena_robot_test \
$(BUILD)/host/tests/dspic30_arena_robot_test: | $(DSPIC30_OUT)/epuck-aseba-factory.hex
