# The e-puck firmware, built here for the host (epuck-emu); the dsPIC build
# compiles the same files with XC16.
LIBRARIES += aseba_epuck_firmware
aseba_epuck_firmware_SOURCES := firmware/epuck_firmware.c firmware/epuck_natives.c
