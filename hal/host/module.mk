# The host board: hal.h over memory and a pluggable world, and the TCP
# network that joins boards and tools.
LIBRARIES += aseba_host_board
aseba_host_board_SOURCES := hal/host/host_board.c hal/host/host_peripherals.c \
                            hal/host/host_memory.c hal/host/host_world.c \
                            hal/host/network.cpp hal/host/network_status.cpp

# epuck-emu: the e-puck firmware image running on a PC.
PROGRAMS += epuck-emu
epuck-emu_SOURCES := hal/host/epuck_emu.cpp
epuck-emu_LIBS := aseba_epuck_firmware aseba_bootloader aseba_epuck_drivers aseba_host_board aseba_compiler aseba_node aseba_vm \
                  aseba_natives
