# Tests of the DSP natives (native_functions/nat_dsp*.c): against expectations
# computed independently in double precision, through direct calls and
# through the VM's NATIVE_CALL; dsp.fft also bit for bit against a model, with
# a deliberately faulty copy (dsp_fft_truncating_mutant.c) it must catch.
TESTS += dsp_natives_test
dsp_natives_test_SOURCES := tests/native_functions_dsp/dsp_node.cpp tests/native_functions_dsp/dsp_expectations.cpp \
                            tests/native_functions_dsp/dsp_fft_test.cpp \
                            tests/native_functions_dsp/dsp_fft_exact_test.cpp \
                            tests/native_functions_dsp/dsp_fft_truncating_mutant.c \
                            tests/native_functions_dsp/dsp_filter_test.cpp \
                            tests/native_functions_dsp/dsp_correlation_test.cpp \
                            tests/native_functions_dsp/dsp_contract_test.cpp \
                            tests/native_functions_dsp/dsp_demo_test.cpp \
                            tests/compiler/reference_oracle.cpp \
                            tests/compiler/reference_containment.cpp
# The demo test compiles examples/sound-direction.aesl with our compiler and,
# as the oracle of the DSP natives' stack layout, with the reference one.
dsp_natives_test_LIBS := aseba_compiler aseba_natives aseba_vm
dsp_natives_test_LDLIBS := -lasebacompiler -lasebacommon -lgtest -lgtest_main -pthread

# One DSP native call, for instruction counts under callgrind (see the file).
PROGRAMS += bench-dsp
bench-dsp_SOURCES := tests/native_functions_dsp/dsp_bench.cpp tests/native_functions_dsp/dsp_node.cpp \
                     tests/native_functions_dsp/dsp_expectations.cpp
bench-dsp_LIBS := aseba_compiler aseba_natives aseba_vm

