# Tests of the VM (vm/), described in tests/vm/README.md. The programs and
# debug tests run twice: on the VM as the host tools use it (computed-goto
# dispatch) and on the switch variant that the dsPIC build uses, a second
# library built from the same source by tests/vm/vm_switch.c.
VM_TEST_GTEST_LDLIBS := -lgtest -lgtest_main -pthread

LIBRARIES += aseba_vm_switch
aseba_vm_switch_SOURCES := tests/vm/vm_switch.c vm/vm_debug.c vm/vm_verify.c vm/vm_native_text.c

VM_PROGRAM_TEST_SOURCES := tests/vm/programs_test.cpp tests/vm/program_script.cpp \
                           tests/vm/operators_test.cpp tests/vm/assembler_test.cpp \
                           tests/vm/verifier_test.cpp

TESTS += vm_programs_test
vm_programs_test_SOURCES := $(VM_PROGRAM_TEST_SOURCES)
vm_programs_test_LIBS := test_support aseba_vm
vm_programs_test_LDLIBS := $(VM_TEST_GTEST_LDLIBS)

TESTS += vm_programs_switch_test
vm_programs_switch_test_SOURCES := $(VM_PROGRAM_TEST_SOURCES)
vm_programs_switch_test_LIBS := test_support aseba_vm_switch
vm_programs_switch_test_LDLIBS := $(VM_TEST_GTEST_LDLIBS)

TESTS += vm_debug_test
vm_debug_test_SOURCES := tests/vm/debug_test.cpp
vm_debug_test_LIBS := test_support aseba_vm
vm_debug_test_LDLIBS := $(VM_TEST_GTEST_LDLIBS)

TESTS += vm_debug_switch_test
vm_debug_switch_test_SOURCES := tests/vm/debug_test.cpp
vm_debug_switch_test_LIBS := test_support aseba_vm_switch
vm_debug_switch_test_LDLIBS := $(VM_TEST_GTEST_LDLIBS)

# Differential tests against Debian's reference VM (package `aseba`,
# /usr/lib/libasebavm.a), whose headers are not ours: no warnings from them.
TESTS += vm_reference_test
vm_reference_test_SOURCES := tests/vm/reference_test.cpp tests/vm/reference_node.cpp \
                             tests/vm/random_program.cpp
vm_reference_test_LIBS := test_support aseba_vm
vm_reference_test_LDLIBS := -lasebavm $(VM_TEST_GTEST_LDLIBS)
EXTRA_CFLAGS_tests/vm/reference_node := -isystem /usr/include/aseba

# Random images and commands; meant for the sanitizer build (`make test`).
# Both dispatch variants: the run loop trusts the verifier in each.
VM_FUZZ_TEST_SOURCES := tests/vm/fuzz_test.cpp tests/vm/fuzz_driver.cpp tests/vm/random_program.cpp
TESTS += vm_fuzz_test
vm_fuzz_test_SOURCES := $(VM_FUZZ_TEST_SOURCES)
vm_fuzz_test_LIBS := test_support aseba_vm
vm_fuzz_test_LDLIBS := $(VM_TEST_GTEST_LDLIBS)

TESTS += vm_fuzz_switch_test
vm_fuzz_switch_test_SOURCES := $(VM_FUZZ_TEST_SOURCES)
vm_fuzz_switch_test_LIBS := test_support aseba_vm_switch
vm_fuzz_switch_test_LDLIBS := $(VM_TEST_GTEST_LDLIBS)

# The verifier on every program a compiler produces: ours and the reference
# (Debian's libasebacompiler, as in tests/compiler), on the upstream corpus,
# the compiler tests' programs, the examples and generated programs.
TESTS += vm_verifier_compiled_test
vm_verifier_compiled_test_SOURCES := tests/vm/verifier_compiled_test.cpp \
                                     tests/compiler/program_generator.cpp \
                                     tests/compiler/test_targets.cpp tests/compiler/corpus.cpp \
                                     tests/compiler/reference_oracle.cpp \
                                     tests/compiler/reference_containment.cpp
vm_verifier_compiled_test_LIBS := aseba_compiler aseba_natives aseba_vm
vm_verifier_compiled_test_LDLIBS := -lasebacompiler -lasebacommon $(VM_TEST_GTEST_LDLIBS)
