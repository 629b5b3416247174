# Tests of the host board (boards/epuck_host): the simulated e-puck's
# clock, scheduler, link, peripherals and memories.
TESTS += host_board_test
host_board_test_SOURCES := tests/boards/epuck_host/host_board_test.cpp
host_board_test_LIBS := aseba_host_board
host_board_test_LDLIBS := -lgtest -lgtest_main -pthread
