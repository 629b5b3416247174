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
