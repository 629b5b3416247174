# Tests of the console: the client library's codec, targets and variables
# (client_test), and `aseba` end to end against epuck-emu (console_test).
TESTS += client_test
client_test_SOURCES := tests/console/codec_test.cpp tests/console/client_units_test.cpp \
                      tests/console/aesl_test.cpp tests/console/format_regressions_test.cpp
client_test_LIBS := aseba_client aseba_compiler aseba_natives aseba_vm
client_test_LDLIBS := -lgtest -lgtest_main -pthread

TESTS += console_test
console_test_SOURCES := tests/console/console_test.cpp tests/console/network_test.cpp \
                        tests/console/reference_test.cpp tests/console/flash_test.cpp \
                        tests/console/flasher_test.cpp \
                        tests/console/robot_ports_test.cpp tests/console/emulator_ports_test.cpp \
                        tests/console/command_line_test.cpp \
                        tests/console/console_support.cpp tests/bootloader/test_images.cpp
console_test_LIBS := aseba_client aseba_flash aseba_host_board aseba_compiler aseba_natives \
                     aseba_node aseba_vm
console_test_LDLIBS := -lgtest -lgtest_main -pthread

# The test starts these programs of its own build (order-only: they are
# run, not linked).
CONSOLE_TEST_PROGRAMS := epuck-emu aseba asebac epuck-image aseba-mqtt aseba-ide
$(foreach v,$(VARIANTS),$(eval \
  $(BUILD)/$(v)/tests/console_test: | $(foreach p,$(CONSOLE_TEST_PROGRAMS),$(BUILD)/$(v)/bin/$(p))))

# `aseba flash` of the dsPIC30 application image that `make dspic30` links:
# the test reads it, so the test program waits for it.
EXTRA_CFLAGS_tests/console/flash_test := '-DDSPIC30_APPLICATION_IMAGE="$(DSPIC30_OUT)/epuck-aseba.hex"'
$(foreach v,$(VARIANTS),$(eval $(BUILD)/$(v)/tests/console_test: | $(DSPIC30_OUT)/epuck-aseba.hex))
