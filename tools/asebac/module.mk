# asebac: compile Aseba scripts and .aesl projects, or run them on the host VM.
PROGRAMS += asebac
asebac_SOURCES := tools/asebac/main.cpp tools/asebac/run.cpp
asebac_LIBS := aseba_compiler aseba_natives aseba_vm

# The plain build links asebac statically: a compile takes about as long as
# the dynamic loader's symbol lookups for libstdc++ did, which the whole
# process paid on every run. (The sanitizers need the dynamic runtime.)
$(BUILD)/host/bin/asebac: asebac_LDLIBS += -static
