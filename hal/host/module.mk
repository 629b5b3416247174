# The host port: hal.h over memory and a pluggable world (the simulated chip
# and board), and a simulated e-puck from power-on: bootloader then firmware
# on a host board. Networks, physics and programs are the emulator's
# (tools/emulator), which uses this port.
LIBRARIES += aseba_host_board
aseba_host_board_SOURCES := hal/host/host_board.c hal/host/host_peripherals.c \
                            hal/host/host_memory.c hal/host/host_world.c

LIBRARIES += aseba_host_robot
aseba_host_robot_SOURCES := hal/host/host_robot.c
