# The e-puck as a robot package: its description and variables, its native
# table, and its devices (devices/), written against hal/hal.h and the
# e-puck's board interface (epuck_board.h). The host links them with the
# simulated board (boards/epuck_host), the dsPIC build
# (ports/dspic30/module.mk) with the real one (boards/epuck_dspic30).
LIBRARIES += aseba_epuck
aseba_epuck_SOURCES := $(sort $(wildcard robots/epuck/*.c robots/epuck/devices/*.c))
