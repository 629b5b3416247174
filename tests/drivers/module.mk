# Tests of the e-puck drivers (drivers/epuck) on the host board, against a
# modelled world (the peripherals as the fact sheet describes them), and of
# the whole firmware image on it.
# Every test file of the folder but the whole image's.
TESTS += drivers_test
drivers_test_SOURCES := $(filter-out tests/drivers/firmware_image_test.cpp,\
                          $(sort $(wildcard tests/drivers/*.cpp)))
drivers_test_LIBS := aseba_epuck_drivers aseba_host_board
drivers_test_LDLIBS := -lgtest -lgtest_main -pthread

TESTS += firmware_image_test
firmware_image_test_SOURCES := tests/drivers/modelled_world.cpp \
                               tests/drivers/firmware_image_test.cpp
firmware_image_test_LIBS := aseba_epuck_firmware aseba_bootloader aseba_epuck_drivers aseba_host_board \
                            aseba_compiler aseba_node aseba_vm aseba_natives
firmware_image_test_LDLIBS := -lgtest -lgtest_main -pthread
