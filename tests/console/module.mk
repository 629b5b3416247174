# Tests of the console: the client library's codec, targets and variables
# (client_test), and `aseba` end to end against epuck-emu (console_test).
TESTS += client_test
client_test_SOURCES := tests/console/codec_test.cpp tests/console/client_units_test.cpp \
                      tests/console/aesl_test.cpp
client_test_LIBS := aseba_client aseba_compiler aseba_natives aseba_vm
client_test_LDLIBS := -lgtest -lgtest_main -pthread

TESTS += console_test
console_test_SOURCES := tests/console/console_test.cpp tests/console/network_test.cpp \
                        tests/console/reference_test.cpp tests/console/flash_test.cpp \
                        tests/console/flasher_test.cpp \
                        tests/console/robot_ports_test.cpp \
                        tests/console/console_support.cpp
console_test_LIBS := aseba_client aseba_flash aseba_host_board aseba_compiler aseba_natives \
                     aseba_node aseba_vm
console_test_LDLIBS := -lgtest -lgtest_main -pthread

# The test starts the plain host builds of these programs (order-only: they
# are run, not linked).
$(BUILD)/host-sanitize/tests/console_test: | $(BUILD)/host/bin/epuck-emu $(BUILD)/host/bin/aseba
