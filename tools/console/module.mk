# aseba: the console for a group of robots (git-style subcommands) over the
# client library.
PROGRAMS += aseba
aseba_SOURCES := tools/console/main.cpp tools/console/options.cpp tools/console/session.cpp \
                 tools/console/commands_program.cpp tools/console/commands_execution.cpp \
                 tools/console/commands_variables.cpp tools/console/commands_events.cpp \
                 tools/console/commands_flash.cpp
aseba_LIBS := aseba_client aseba_flash aseba_compiler aseba_natives aseba_node aseba_vm
