# Helpers shared by the tests: the bytecode assembler and a VM harness
# (memory with guard words, message log, tiny test natives). Programs that
# link test_support also link a VM library after it (aseba_vm or aseba_vm_switch).
LIBRARIES += test_support
test_support_SOURCES := tests/support/assembler.cpp tests/support/vm_harness.cpp
