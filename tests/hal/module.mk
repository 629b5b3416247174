# Tests of the hardware abstraction layer: hal/dspic30 compiled on the PC
# against a simulated register file (tests/hal/simulated_chip.cpp), and the
# host board's simulated peripherals.
HAL_TEST_GTEST_LDLIBS := -lgtest -lgtest_main -pthread

# Every hal/dspic30 source but the DSP kernel (tests/native_functions_dsp)
# and the bootloader image's entry point, built with the dsPIC target's
# configuration and the simulated register mapping; the application's entry
# point is renamed so that it does not clash with GoogleTest's.
HAL_DSPIC30_SOURCES := $(filter-out hal/dspic30/dspic30_dsp_kernel.c hal/dspic30/dspic30_bootloader_main.c,\
                         $(wildcard hal/dspic30/*.c)) hal/hal_link_rings.c
$(foreach s,$(HAL_DSPIC30_SOURCES),\
  $(eval EXTRA_CFLAGS_$(basename $(s)) += -DDSPIC30_SIMULATED_REGISTERS -UTARGET_CONFIG \
                                          '-DTARGET_CONFIG="hal/dspic30/dspic30_config.h"'))
EXTRA_CFLAGS_hal/dspic30/dspic30_application_main += -Dmain=dspic30_main
EXTRA_CFLAGS_tests/hal/dspic30_test := -UTARGET_CONFIG '-DTARGET_CONFIG="hal/dspic30/dspic30_config.h"'

TESTS += hal_dspic30_test
hal_dspic30_test_SOURCES := tests/hal/dspic30_test.cpp tests/hal/simulated_chip.cpp \
                            $(HAL_DSPIC30_SOURCES)
hal_dspic30_test_LIBS := aseba_epuck_firmware aseba_bootloader aseba_epuck_drivers aseba_node aseba_vm aseba_natives
hal_dspic30_test_LDLIBS := $(HAL_TEST_GTEST_LDLIBS)

TESTS += hal_host_test
hal_host_test_SOURCES := tests/hal/host_board_test.cpp
hal_host_test_LIBS := aseba_host_board
hal_host_test_LDLIBS := $(HAL_TEST_GTEST_LDLIBS)
