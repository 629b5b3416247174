# The simulated arena (hal/host: arena files, the Enki world, the lockstep
# simulation) end to end through the real drivers and firmware.
TESTS += arena_test
arena_test_SOURCES := tests/arena/arena_file_test.cpp tests/arena/arena_sensing_test.cpp
arena_test_LIBS := aseba_arena aseba_host_robot aseba_flash aseba_epuck_firmware aseba_bootloader aseba_epuck_drivers \
                   aseba_host_board aseba_compiler aseba_node aseba_vm aseba_natives
arena_test_LDLIBS := -lenki -lgtest -lgtest_main -pthread
