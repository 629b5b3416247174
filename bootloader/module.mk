# The fail-safe record store (bytecode, settings) and the serial bootloader's
# core, portable C99 on hal.h.
LIBRARIES += aseba_bootloader
aseba_bootloader_SOURCES := bootloader/bytecode_store.c bootloader/boot_application.c \
                            bootloader/bootloader.c
