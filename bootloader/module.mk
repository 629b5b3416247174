# The serial bootloader's core and the application's descriptor, portable
# C99 on hal.h.
LIBRARIES += aseba_bootloader
aseba_bootloader_SOURCES := bootloader/boot_application.c bootloader/bootloader.c
