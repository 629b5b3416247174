# Focused tests of the compiler library: lexer, the code generation listings
# of the specifications word for word, every error message at its position,
# and the project's own formats (targets in JSON, .aesl, listings).
TESTS += compiler_unit_test
compiler_unit_test_SOURCES := tests/compiler_unit/lexer_test.cpp \
                              tests/compiler_unit/codegen_test.cpp \
                              tests/compiler_unit/errors_test.cpp \
                              tests/compiler_unit/formats_test.cpp \
                              tests/compiler_unit/language_test.cpp \
                              tests/compiler_unit/limits_test.cpp \
                              tests/compiler_unit/tools_test.cpp \
                              tools/asebac/run.cpp
compiler_unit_test_LIBS := aseba_compiler aseba_natives aseba_vm
compiler_unit_test_LDLIBS := -lgtest -lgtest_main -pthread
