# The native functions of Aseba (language.md §13) and the DSP ones, portable
# C99 like the VM: host tools and every firmware target build the same
# files, every file of the folder (a port may replace the DSP kernel).
LIBRARIES += aseba_natives
aseba_natives_SOURCES := $(sort $(wildcard native_functions/*.c))
