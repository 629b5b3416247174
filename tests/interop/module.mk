# Interoperability of epuck-emu with the reference Aseba tools of Debian's
# `aseba` package (asebamassloader, asebadump, asebacmd, asebaswitch,
# asebahttp): the test starts epuck-emu and the tools on loopback and watches
# the robots with its own protocol client.
TESTS += interop_test
interop_test_SOURCES := tests/interop/interop_test.cpp tests/interop/aseba_client.cpp \
                        tests/interop/child_process.cpp tests/interop/interop_support.cpp \
                        tests/bootloader/test_images.cpp
interop_test_LIBS := aseba_compiler aseba_flash aseba_node aseba_natives aseba_vm
interop_test_LDLIBS := -lgtest -lgtest_main -pthread

# The test runs the emulator and epuck-image of its own build (order-only:
# they are programs to start, not something to link).
$(foreach v,$(VARIANTS),$(eval \
  $(BUILD)/$(v)/tests/interop_test: | $(BUILD)/$(v)/bin/epuck-emu $(BUILD)/$(v)/bin/epuck-image))
