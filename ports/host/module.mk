# The host port: a simulated e-puck from power-on, its image's entry point
# (bootloader, then firmware, on the host board of boards/epuck_host). The
# host has no chip code of its own: the board simulates the chip.
LIBRARIES += aseba_host_robot
aseba_host_robot_SOURCES := ports/host/host_robot.c
