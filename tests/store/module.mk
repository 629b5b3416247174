# Tests of the fail-safe bytecode store (store/) on the host board, with
# power cuts at every flash operation.
TESTS += store_test
store_test_SOURCES := tests/store/store_test.cpp
store_test_LIBS := aseba_store aseba_epuck aseba_host_board aseba_node
store_test_LDLIBS := -lgtest -lgtest_main -pthread
