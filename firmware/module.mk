# The firmware's main loop, robot-neutral: built here for the host, with the
# host target's robot (epuck-emu); the chip builds compile the same file
# with their own configuration.
LIBRARIES += aseba_firmware
aseba_firmware_SOURCES := firmware/firmware.c
