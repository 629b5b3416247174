# Tests of the e-puck drivers (drivers/epuck) on the host board, against a
# modelled world (the peripherals as the fact sheet describes them), and of
# the whole firmware image on it.
TESTS += drivers_test
drivers_test_SOURCES := tests/drivers/modelled_world.cpp tests/drivers/motors_test.cpp \
                        tests/drivers/analog_test.cpp \
                        tests/drivers/board_io_test.cpp tests/drivers/rc5_test.cpp \
                        tests/drivers/camera_test.cpp
drivers_test_LIBS := aseba_epuck_drivers aseba_host_board
drivers_test_LDLIBS := -lgtest -lgtest_main -pthread

TESTS += firmware_image_test
firmware_image_test_SOURCES := tests/drivers/modelled_world.cpp \
                               tests/drivers/firmware_image_test.cpp
firmware_image_test_LIBS := aseba_epuck_firmware aseba_bootloader aseba_epuck_drivers aseba_host_board \
                            aseba_compiler aseba_node aseba_vm aseba_natives
firmware_image_test_LDLIBS := -lgtest -lgtest_main -pthread
