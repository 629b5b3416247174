# Tests of the chip-neutral boundary's shared code (hal/): the link's rings,
# at the e-puck's capacities. hal/hal_link_rings.c has one object in the
# host build, compiled with the dsPIC target's configuration
# (tests/ports/dspic30/module.mk): the test is too, so that both see the
# same rings.
TESTS += link_rings_test
link_rings_test_SOURCES := tests/hal/link_rings_test.cpp hal/hal_link_rings.c
link_rings_test_LDLIBS := -lgtest -lgtest_main -pthread
EXTRA_CFLAGS_tests/hal/link_rings_test := -UTARGET_CONFIG \
    '-DTARGET_CONFIG="boards/epuck_dspic30/epuck_dspic30_config.h"'
