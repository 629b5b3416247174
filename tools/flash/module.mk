# aseba_flash: Microchip Intel HEX images read, written and cut into Aseba
# bootloader pages, with the application descriptor the bootloader checks,
# the e-puck's bootloader and factory images, and the row packets of the
# factory Tiny Bootloader for the first installation.
LIBRARIES += aseba_flash
aseba_flash_SOURCES := tools/flash/hex_image.cpp tools/flash/epuck_image.cpp \
                       tools/flash/tiny_bootloader.cpp

# epuck-image: the last step of `make dspic30` (hal/dspic30/module.mk).
PROGRAMS += epuck-image
epuck-image_SOURCES := tools/flash/epuck_image_main.cpp
epuck-image_LIBS := aseba_flash aseba_node
