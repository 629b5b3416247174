# The e-puck's devices, written against hal/hal.h and the e-puck's board
# (epuck_board.h): the host links them with hal/host, the dsPIC build
# (hal/dspic30/module.mk) with the chip.
LIBRARIES += aseba_epuck_drivers
aseba_epuck_drivers_SOURCES := $(sort $(wildcard drivers/epuck/*.c))
