# aseba_flash: Microchip Intel HEX images read, written and cut into Aseba
# bootloader pages, with the application descriptor the bootloader checks,
# the e-puck's bootloader and factory images, and the row packets of the
# factory Tiny Bootloader for the first installation.
LIBRARIES += aseba_flash
aseba_flash_SOURCES := tools/flash/hex_image.cpp tools/flash/epuck_image.cpp \
                       tools/flash/tiny_bootloader.cpp

# aseba_tiny_upload: sends those packets to the Tiny Bootloader (its
# protocol over any byte link, the serial link through aseba_client's
# transport) and the `epuck-image install` command.
LIBRARIES += aseba_tiny_upload
aseba_tiny_upload_SOURCES := tools/flash/tiny_upload.cpp tools/flash/tiny_serial_link.cpp \
                             tools/flash/install_command.cpp

# epuck-image: the last step of `make dspic30` (ports/dspic30/module.mk), and
# `epuck-image install` for the first installation on a robot.
PROGRAMS += epuck-image
epuck-image_SOURCES := tools/flash/epuck_image_main.cpp
epuck-image_LIBS := aseba_tiny_upload aseba_client aseba_flash aseba_node
