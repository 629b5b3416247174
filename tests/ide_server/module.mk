# The IDE server: its request parser as data, its project and binary files
# against aesl.md and the reference (libasebacommon, an oracle only), and the
# whole server through WebSockets against epuck-emu (message traces as data).
TESTS += ide_server_test
ide_server_test_SOURCES := tests/ide_server/requests_test.cpp tests/ide_server/binary_file_test.cpp \
                           tests/ide_server/workspace_test.cpp tests/ide_server/server_test.cpp \
                           tests/ide_server/websocket_client.cpp tests/console/console_support.cpp
ide_server_test_LIBS := aseba_ide aseba_client aseba_compiler aseba_natives aseba_node aseba_vm
ide_server_test_LDLIBS := -lasebacommon -lpugixml -lgtest -lgtest_main -pthread
EXTRA_CFLAGS_tests/ide_server/websocket_client := -std=c++17
EXTRA_CFLAGS_tests/ide_server/binary_file_test := -isystem /usr/include/aseba

# The test starts epuck-emu and aseba-ide of its own build (order-only: run,
# not linked).
$(foreach v,$(VARIANTS),$(eval $(BUILD)/$(v)/tests/ide_server_test: | $(BUILD)/$(v)/bin/epuck-emu $(BUILD)/$(v)/bin/aseba-ide))
