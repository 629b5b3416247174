# Tests of the hardware abstraction layer: hal/dspic30 compiled on the PC
# against a simulated register file (tests/hal/simulated_chip.cpp), and the
# host board's simulated peripherals.
HAL_TEST_GTEST_LDLIBS := -lgtest -lgtest_main -pthread

# Every hal/dspic30 source, built with the simulated register mapping; the
# entry point is renamed so that it does not clash with GoogleTest's.
HAL_DSPIC30_SOURCES := $(wildcard hal/dspic30/*.c)
$(foreach s,$(HAL_DSPIC30_SOURCES),\
  $(eval EXTRA_CFLAGS_$(basename $(s)) += -DDSPIC30_SIMULATED_REGISTERS))
EXTRA_CFLAGS_hal/dspic30/dspic30_main += -Dmain=dspic30_main

TESTS += hal_dspic30_test
hal_dspic30_test_SOURCES := tests/hal/dspic30_test.cpp tests/hal/simulated_chip.cpp \
                            $(HAL_DSPIC30_SOURCES)
hal_dspic30_test_LIBS := aseba_epuck_firmware aseba_bootloader aseba_epuck_drivers aseba_node aseba_vm aseba_natives
hal_dspic30_test_LDLIBS := $(HAL_TEST_GTEST_LDLIBS)

TESTS += hal_host_test
hal_host_test_SOURCES := tests/hal/host_board_test.cpp
hal_host_test_LIBS := aseba_host_board
hal_host_test_LDLIBS := $(HAL_TEST_GTEST_LDLIBS)
