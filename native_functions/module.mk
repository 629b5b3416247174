# The standard native functions of Aseba (language.md §13), portable C99 like
# the VM: host tools and every firmware target build the same files.
LIBRARIES += aseba_natives
aseba_natives_SOURCES := native_functions/nat_arguments.c native_functions/nat_math.c \
                         native_functions/nat_trigonometry.c native_functions/nat_deque.c \
                         native_functions/nat_standard.c
aseba_natives_SOURCES += native_functions/nat_dsp.c native_functions/nat_dsp_fft.c \
                         native_functions/nat_dsp_filter.c native_functions/nat_dsp_correlation.c \
                         native_functions/nat_dsp_kernel.c
