# The whole firmware (firmware/, with the e-puck of robots/epuck) on the host
# board, in the modelled world of tests/robots/epuck.
TESTS += firmware_image_test
firmware_image_test_SOURCES := tests/robots/epuck/modelled_world.cpp \
                               tests/firmware/firmware_image_test.cpp
firmware_image_test_LIBS := aseba_firmware aseba_epuck aseba_store aseba_bootloader aseba_host_board \
                            aseba_compiler aseba_node aseba_vm aseba_natives
firmware_image_test_LDLIBS := -lgtest -lgtest_main -pthread
