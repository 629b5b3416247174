# Tests of the firmware on the emulated STM32F4 (QEMU's netduinoplus2, built
# by `make stm32f4`):
#
#   qemu_node_test          the e-puck image as users reach it: discovered by
#                           `aseba nodes`, loaded by asebamassloader and the
#                           console, variables, events both ways, breakpoints
#                           and stepping, the paper's controller on fed values
#   qemu_vm_programs_test   tests/vm's program tests, unchanged, their VM on
#   qemu_node_traces_test   the Cortex-M4; tests/node's trace tests, likewise:
#                           remote_vm.cpp and remote_node.cpp stand for vm.h
#                           and node.h, each call run by the harness image
#                           (tests/ports/stm32f4/target) and its effects brought back
#
# Each starts QEMU on a free loopback port (scripts/qemu-node.sh) and stops
# it by its PID.

STM32F4_HARNESS := $(STM32F4_OUT)/aseba-harness-stm32f4
STM32F4_HARNESS_SOURCES := $(sort $(wildcard vm/*.c native_functions/*.c tests/ports/stm32f4/target/*.c)) \
                           ports/stm32f4/stm32f4_startup.c ports/stm32f4/stm32f4_clock.c \
                           ports/stm32f4/stm32f4_usart.c hal/hal_link_rings.c
STM32F4_HARNESS_OBJECTS := $(patsubst %.c,$(STM32F4_OUT)/obj/%.o,$(STM32F4_HARNESS_SOURCES))

$(STM32F4_HARNESS).elf: $(STM32F4_HARNESS_OBJECTS) $(STM32F4_SCRIPT)
	$(STM32F4_CC) $(STM32F4_ARCH) -nostartfiles --specs=nano.specs -T $(STM32F4_SCRIPT) \
	    -Wl,--gc-sections $(STM32F4_HARNESS_OBJECTS) -lc -lgcc -o $@

-include $(STM32F4_HARNESS_OBJECTS:.o=.d)

QEMU_TEST_LDLIBS := -lgtest -lgtest_main -pthread
QEMU_MACHINE_SOURCES := tests/ports/stm32f4/qemu_machine.cpp tests/interop/child_process.cpp \
                        tests/interop/interop_support.cpp
QEMU_REMOTE_SOURCES := tests/ports/stm32f4/remote_link.cpp tests/ports/stm32f4/qemu_link.cpp \
                       $(QEMU_MACHINE_SOURCES)
EXTRA_CFLAGS_tests/ports/stm32f4/qemu_link := '-DQEMU_HARNESS_IMAGE="$(STM32F4_HARNESS).elf"'

TESTS += qemu_vm_programs_test
qemu_vm_programs_test_SOURCES := tests/vm/programs_test.cpp tests/vm/program_script.cpp \
                                 tests/ports/stm32f4/remote_vm.cpp $(QEMU_REMOTE_SOURCES)
qemu_vm_programs_test_LIBS := test_support
qemu_vm_programs_test_LDLIBS := $(QEMU_TEST_LDLIBS)

TESTS += qemu_node_traces_test
qemu_node_traces_test_SOURCES := tests/node/trace_test.cpp tests/node/node_harness.cpp \
                                 tests/node/reference_decoder.cpp tests/ports/stm32f4/remote_node.cpp \
                                 tests/ports/stm32f4/remote_vm.cpp vm/node_description.c vm/node_send.c \
                                 vm/node_crc.c vm/vm_native_text.c \
                                 $(QEMU_REMOTE_SOURCES)
qemu_node_traces_test_LIBS := aseba_natives
qemu_node_traces_test_LDLIBS := -lasebacommon $(QEMU_TEST_LDLIBS)

TESTS += qemu_node_test
qemu_node_test_SOURCES := tests/ports/stm32f4/node_test.cpp $(QEMU_MACHINE_SOURCES)
qemu_node_test_LDLIBS := $(QEMU_TEST_LDLIBS)
EXTRA_CFLAGS_tests/ports/stm32f4/node_test := '-DQEMU_NODE_IMAGE="$(STM32F4_IMAGE).elf"' \
    '-DASEBA_CONSOLE="$(BUILD)/host-sanitize/bin/aseba"'

# The images and the console these tests run; order-only, so that they do
# not enter the link.
$(BUILD)/host-sanitize/tests/qemu_vm_programs_test \
$(BUILD)/host-sanitize/tests/qemu_node_traces_test: | $(STM32F4_HARNESS).elf
$(BUILD)/host-sanitize/tests/qemu_node_test: | $(STM32F4_IMAGE).elf $(BUILD)/host-sanitize/bin/aseba

# The VM's instructions per bytecode step on the Cortex-M4, for `make bench`.
PROGRAMS += bench-qemu
bench-qemu_SOURCES := tests/ports/stm32f4/qemu_bench.cpp tests/ports/stm32f4/remote_vm.cpp vm/vm_native_text.c \
                      $(QEMU_REMOTE_SOURCES)
bench-qemu_LIBS := test_support aseba_compiler aseba_natives
$(BUILD)/host/bin/bench-qemu: | $(STM32F4_HARNESS).elf
