# The host board: hal.h over memory and a pluggable world, and the TCP
# network that joins boards and tools.
LIBRARIES += aseba_host_board
aseba_host_board_SOURCES := hal/host/host_board.c hal/host/host_peripherals.c \
                            hal/host/host_memory.c hal/host/host_world.c \
                            hal/host/network.cpp hal/host/network_status.cpp

# A simulated e-puck from power-on: bootloader then firmware on a host board,
# and what its memories hold before it starts.
LIBRARIES += aseba_host_robot
aseba_host_robot_SOURCES := hal/host/host_robot.c hal/host/robot_memory.cpp

# The simulated arena: e-pucks in an Enki world (Debian libenki-dev, GPL-2+),
# each on a host board with the real firmware, on one network.
LIBRARIES += aseba_arena
aseba_arena_SOURCES := hal/host/arena_file.cpp hal/host/enki_world.cpp \
                       hal/host/arena_simulation.cpp

# epuck-emu: the e-puck firmware image running on a PC.
PROGRAMS += epuck-emu
epuck-emu_SOURCES := hal/host/epuck_emu.cpp
epuck-emu_LIBS := aseba_arena aseba_host_robot aseba_flash aseba_epuck_firmware aseba_bootloader aseba_epuck_drivers \
                  aseba_host_board aseba_compiler aseba_node aseba_vm aseba_natives
epuck-emu_LDLIBS := -lenki
