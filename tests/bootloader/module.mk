# Tests of the serial bootloader, and of the HEX reader and writer, the
# e-puck images and the linker scripts against the flash layout
# (tools/flash, linker/: tests/README.md), on the host board with power cuts.
TESTS += bootloader_hex_test
bootloader_hex_test_SOURCES := tests/bootloader/hex_test.cpp tests/bootloader/tiny_bootloader_test.cpp \
                              tests/bootloader/epuck_image_test.cpp tests/bootloader/test_images.cpp
bootloader_hex_test_LIBS := aseba_flash aseba_node
bootloader_hex_test_LDLIBS := -lgtest -lgtest_main -pthread

TESTS += bootloader_protocol_test
bootloader_protocol_test_SOURCES := tests/bootloader/bootloader_test.cpp
bootloader_protocol_test_LIBS := aseba_flash aseba_bootloader aseba_host_board aseba_node
bootloader_protocol_test_LDLIBS := -lgtest -lgtest_main -pthread

TESTS += bootloader_linker_scripts_test
bootloader_linker_scripts_test_SOURCES := tests/bootloader/linker_scripts_test.cpp
bootloader_linker_scripts_test_LDLIBS := -lgtest -lgtest_main -pthread

TESTS += bootloader_tiny_upload_test
bootloader_tiny_upload_test_SOURCES := tests/bootloader/tiny_upload_test.cpp \
                                       tests/bootloader/tiny_simulator.cpp \
                                       tests/bootloader/test_images.cpp
bootloader_tiny_upload_test_LIBS := aseba_tiny_upload aseba_client aseba_flash aseba_bootloader \
                                    aseba_host_board aseba_node
bootloader_tiny_upload_test_LDLIBS := -lgtest -lgtest_main -pthread
