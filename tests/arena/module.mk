# The simulated arena (tools/emulator: arena files, the Enki world, the lockstep
# simulation) end to end through the real drivers and firmware.
TESTS += arena_test
arena_test_SOURCES := tests/arena/arena_file_test.cpp tests/arena/arena_sensing_test.cpp \
                      tests/arena/sound_test.cpp tests/arena/inputs_test.cpp \
                      tests/arena/control_test.cpp tests/arena/partitioned_world_test.cpp \
                      tests/arena/ir_sensor_test.cpp
arena_test_LIBS := aseba_arena aseba_emulator_network aseba_host_robot aseba_flash aseba_firmware aseba_epuck aseba_store \
                   aseba_bootloader aseba_host_board aseba_compiler aseba_node aseba_vm aseba_natives
arena_test_LDLIBS := -lenki -lgtest -lgtest_main -pthread

# The dangerous-area experiment (experiments/dangerous-areas) and the
# network's switch for the robots' radio.
TESTS += arena_experiment_test
arena_experiment_test_SOURCES := tests/arena/dangerous_areas_test.cpp \
                                 tests/arena/network_relay_test.cpp
arena_experiment_test_LIBS = aseba_dangerous_areas $(arena_test_LIBS)
arena_experiment_test_LDLIBS = $(arena_test_LDLIBS)

# The network on bare host boards and loopback sockets: per-robot ports, and
# what no client can do (flood it, stall it, reach it from afar), and every
# frame crossing once and in order.
TESTS += network_test
network_test_SOURCES := tests/arena/network_robot_port_test.cpp \
                      tests/arena/network_limits_test.cpp tests/arena/network_order_test.cpp
network_test_LIBS := aseba_emulator_network aseba_host_board
network_test_LDLIBS := -lgtest -lgtest_main -pthread
