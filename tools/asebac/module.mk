# asebac: compile Aseba scripts and .aesl projects, or run them on the host VM.
PROGRAMS += asebac
asebac_SOURCES := tools/asebac/main.cpp tools/asebac/run.cpp
asebac_LIBS := aseba_compiler aseba_natives aseba_vm
