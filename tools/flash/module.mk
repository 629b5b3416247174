# aseba_flash: Microchip Intel HEX images cut into Aseba bootloader pages,
# with the application descriptor the bootloader checks, and the row packets
# of the factory Tiny Bootloader for the first installation.
LIBRARIES += aseba_flash
aseba_flash_SOURCES := tools/flash/hex_image.cpp tools/flash/tiny_bootloader.cpp
