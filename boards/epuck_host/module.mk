# The host board: the simulated e-puck on a PC. hal.h and the e-puck's board
# interface (robots/epuck/epuck_board.h) over memory, with the chip
# simulated along (time in cycles, the link, flash and EEPROM) and a
# pluggable world for what the pins see. Networks, physics and programs are
# the emulator's (tools/emulator), which uses this board.
LIBRARIES += aseba_host_board
aseba_host_board_SOURCES := boards/epuck_host/host_board.c boards/epuck_host/host_peripherals.c \
                            boards/epuck_host/host_memory.c boards/epuck_host/host_world.c
