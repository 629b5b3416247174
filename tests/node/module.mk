# Tests of the node (vm/node*.c): message traces, robustness against any byte
# stream, descriptions and fingerprints. Every frame the node sends is judged
# by a strict decoder written from the spec and by Debian's message library
# (libasebacommon, the reference, used as an oracle only). The standard
# natives give the reference node of protocol.md its 30 native descriptions.
TESTS += node_test
node_test_SOURCES := tests/node/node_harness.cpp tests/node/reference_decoder.cpp \
                     tests/node/trace_test.cpp tests/node/robustness_test.cpp \
                     tests/node/description_test.cpp
node_test_LIBS := aseba_node aseba_compiler aseba_natives aseba_vm
node_test_LDLIBS := -lasebacommon -lgtest -lgtest_main -pthread

# The reference headers are not ours: no warnings from them.
EXTRA_CFLAGS_tests/node/reference_decoder := -isystem /usr/include/aseba
