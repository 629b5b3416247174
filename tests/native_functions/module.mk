# Tests of the standard natives: against the specification's expectations
# (computed independently in the tests) and, bit for bit, against the natives
# of Debian's reference VM library (/usr/lib/libasebavm.a).
TESTS += natives_test
natives_test_SOURCES := tests/native_functions/our_node.cpp tests/native_functions/our_node_common.cpp \
                        tests/native_functions/reference_node.cpp \
                        tests/native_functions/natives_spec_test.cpp \
                        tests/native_functions/natives_deque_test.cpp \
                        tests/native_functions/natives_description_test.cpp \
                        tests/native_functions/natives_reference_test.cpp \
                        tests/native_functions/natives_vm_test.cpp
natives_test_LIBS := aseba_compiler aseba_natives aseba_vm
natives_test_LDLIBS := -lasebavm -lgtest -lgtest_main -pthread

# The reference headers are not ours: no warnings from them.
EXTRA_CFLAGS_tests/native_functions/reference_node := -isystem /usr/include/aseba
EXTRA_CFLAGS_tests/native_functions/natives_reference_test := -isystem /usr/include/aseba
EXTRA_CFLAGS_tests/native_functions/natives_description_test := -isystem /usr/include/aseba
