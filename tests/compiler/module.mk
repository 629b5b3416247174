# Compiler tests. The upstream corpus runs on our compiler, VM and natives;
# the differential, prefix and oracle tests also link Debian's reference
# compiler (package `aseba`, static libraries in /usr/lib), the oracle that
# language.md says we must match.
COMPILER_TEST_SUPPORT := tests/compiler/test_targets.cpp tests/compiler/corpus.cpp \
                         tests/compiler/bytecode_listing.cpp
REFERENCE_ORACLE_SOURCES := tests/compiler/reference_oracle.cpp \
                            tests/compiler/reference_containment.cpp \
                            tests/compiler/error_wording.cpp
COMPILER_TEST_LIBS := aseba_compiler aseba_natives aseba_vm
REFERENCE_COMPILER_LDLIBS := -lasebacompiler -lasebacommon
GTEST_LDLIBS := -lgtest -lgtest_main -pthread

# The reference headers are not ours: no warnings from them.
EXTRA_CFLAGS_tests/compiler/reference_oracle := -isystem /usr/include/aseba

TESTS += compiler_corpus_test
compiler_corpus_test_SOURCES := tests/compiler/corpus_test.cpp $(COMPILER_TEST_SUPPORT)
compiler_corpus_test_LIBS := $(COMPILER_TEST_LIBS)
compiler_corpus_test_LDLIBS := $(GTEST_LDLIBS)

TESTS += compiler_reference_oracle_test
compiler_reference_oracle_test_SOURCES := tests/compiler/reference_oracle_test.cpp \
                                          $(REFERENCE_ORACLE_SOURCES) $(COMPILER_TEST_SUPPORT)
compiler_reference_oracle_test_LDLIBS := $(REFERENCE_COMPILER_LDLIBS) $(GTEST_LDLIBS)

TESTS += compiler_differential_test
compiler_differential_test_SOURCES := tests/compiler/differential_test.cpp \
                                      tests/compiler/program_generator.cpp \
                                      $(REFERENCE_ORACLE_SOURCES) $(COMPILER_TEST_SUPPORT)
compiler_differential_test_LIBS := $(COMPILER_TEST_LIBS)
compiler_differential_test_LDLIBS := $(REFERENCE_COMPILER_LDLIBS) $(GTEST_LDLIBS)

TESTS += compiler_prefix_test
compiler_prefix_test_SOURCES := tests/compiler/prefix_test.cpp $(REFERENCE_ORACLE_SOURCES) \
                                $(COMPILER_TEST_SUPPORT)
compiler_prefix_test_LIBS := $(COMPILER_TEST_LIBS)
compiler_prefix_test_LDLIBS := $(REFERENCE_COMPILER_LDLIBS) $(GTEST_LDLIBS)
