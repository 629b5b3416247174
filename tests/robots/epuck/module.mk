# Tests of the e-puck's devices (robots/epuck/devices) on the host board,
# against a modelled world (the peripherals as the fact sheet describes
# them); tests/firmware runs the whole firmware on the same world.
TESTS += epuck_devices_test
epuck_devices_test_SOURCES := $(sort $(wildcard tests/robots/epuck/*.cpp))
epuck_devices_test_LIBS := aseba_epuck aseba_host_board
epuck_devices_test_LDLIBS := -lgtest -lgtest_main -pthread
