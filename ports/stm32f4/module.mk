# The STM32F4 build of the e-puck firmware, with Debian's GCC cross compiler
# (gcc-arm-none-eabi, newlib for memset and memcpy):
#
#   make stm32f4                    (or: make TARGET=stm32f4)
#
# gives, in build/stm32f4/: epuck-aseba-stm32f4.elf, its Intel HEX image
# (.hex) and its link map (.map), linked with linker/stm32f4-app.ld, for the
# board STM32F4_BOARD names; today the only board is `qemu`, QEMU's
# netduinoplus2 (scripts/qemu-node.sh runs it). A board is one configuration
# header and the sources that differ: its flash backend and its robot's
# board layer.

STM32F4_BOARD ?= qemu
STM32F4_OUT := $(BUILD)/stm32f4
STM32F4_IMAGE := $(STM32F4_OUT)/epuck-aseba-stm32f4
STM32F4_CC := arm-none-eabi-gcc

STM32F4_CONFIG_qemu := boards/netduinoplus2/netduinoplus2_config.h
STM32F4_BOARD_SOURCES_qemu := ports/stm32f4/stm32f4_ram_flash.c $(wildcard boards/netduinoplus2/*.c) \
                              $(wildcard robots/epuck/*.c)

STM32F4_TARGET_CONFIG := '-DTARGET_CONFIG="$(STM32F4_CONFIG_$(STM32F4_BOARD))"'
# The portable layers, the firmware, the port and the board's parts (its
# flash backend, its robot's package and devices); the real chip's flash
# driver (stm32f4_flash.c) is for boards that can write their flash.
STM32F4_PORT_SOURCES := ports/stm32f4/stm32f4_startup.c ports/stm32f4/stm32f4_clock.c \
                        ports/stm32f4/stm32f4_usart.c ports/stm32f4/stm32f4_application_main.c \
                        hal/hal_link_rings.c
STM32F4_FIRMWARE_SOURCES := $(sort $(wildcard vm/*.c native_functions/*.c firmware/*.c) \
                                   store/bytecode_store.c)
STM32F4_SOURCES := $(STM32F4_FIRMWARE_SOURCES) $(STM32F4_PORT_SOURCES) \
                   $(STM32F4_BOARD_SOURCES_$(STM32F4_BOARD))
STM32F4_OBJECTS := $(patsubst %.c,$(STM32F4_OUT)/obj/%.o,$(STM32F4_SOURCES))
STM32F4_SCRIPT := linker/stm32f4-app.ld
# Cortex-M4 without the FPU (the firmware has no floating point); -O2 for
# the VM's speed, the flash has room.
STM32F4_ARCH := -mcpu=cortex-m4 -mthumb -mfloat-abi=soft
STM32F4_CFLAGS := $(STM32F4_ARCH) $(C_STANDARD) $(WARNINGS) -O2 -g -ffreestanding \
                  -ffunction-sections -fdata-sections -I. -Ivm -Inative_functions \
                  $(STM32F4_TARGET_CONFIG)
STM32F4_LDFLAGS := $(STM32F4_ARCH) -nostartfiles --specs=nano.specs -T $(STM32F4_SCRIPT) \
                   -Wl,--gc-sections,-Map=$(STM32F4_IMAGE).map

ifeq ($(TARGET),stm32f4)
.DEFAULT_GOAL := stm32f4
endif

.PHONY: stm32f4
stm32f4: $(STM32F4_IMAGE).elf $(STM32F4_IMAGE).hex
	@arm-none-eabi-size $(STM32F4_IMAGE).elf

# The ARM compiler is in two groups: `cross` (make stm32f4, cross-check) and
# `test` (the QEMU tests' images); `make test` installs only the second.
STM32F4_DEPS_STAMP := $(if $(filter test,$(MAKECMDGOALS)),$(TEST_DEPS_STAMP),$(CROSS_DEPS_STAMP))

$(STM32F4_OUT)/obj/%.o: %.c | $(DEPS_STAMP) $(STM32F4_DEPS_STAMP)
	@mkdir -p $(@D)
	$(STM32F4_CC) $(STM32F4_CFLAGS) -MMD -MP -c $< -o $@

$(STM32F4_IMAGE).elf: $(STM32F4_OBJECTS) $(STM32F4_SCRIPT)
	$(STM32F4_CC) $(STM32F4_LDFLAGS) $(STM32F4_OBJECTS) -lc -lgcc -o $@

$(STM32F4_IMAGE).hex: $(STM32F4_IMAGE).elf
	arm-none-eabi-objcopy -O ihex $< $@

-include $(STM32F4_OBJECTS:.o=.d)

# Every file of the port compiled, warnings as errors, the real chip's flash
# driver included (no board links it yet); part of `make cross-check`.
STM32F4_CHECK_SOURCES := $(wildcard ports/stm32f4/*.c)
.PHONY: stm32f4-check
stm32f4-check: | $(DEPS_STAMP) $(CROSS_DEPS_STAMP)
	@mkdir -p $(BUILD)/cross-stm32f4
	@for source in $(STM32F4_CHECK_SOURCES); do \
	    $(STM32F4_CC) $(STM32F4_CFLAGS) -c $$source \
	        -o $(BUILD)/cross-stm32f4/$$(basename $${source%.c}).o || exit 1; \
	done
	@echo "== ports/stm32f4: $(words $(STM32F4_CHECK_SOURCES)) files build with arm-none-eabi-gcc"

cross-check: stm32f4-check
