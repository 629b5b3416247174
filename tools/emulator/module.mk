# The emulator: simulated e-pucks (boards/epuck_host) joined in one TCP network, what
# their memories hold before they start, and the arena.

# The network that joins host boards and tools, as a Bluetooth switch would.
LIBRARIES += aseba_emulator_network
aseba_emulator_network_SOURCES := tools/emulator/network.cpp tools/emulator/network_status.cpp

# The simulated arena: e-pucks in an Enki world (Debian libenki-dev, GPL-2+),
# each on a host board with the real firmware, on one network; and the
# robots' memories (flash images, stored programs) kept between runs.
LIBRARIES += aseba_arena
aseba_arena_SOURCES := tools/emulator/arena_file.cpp tools/emulator/enki_world.cpp \
                       tools/emulator/partitioned_world.cpp tools/emulator/worker_pool.cpp \
                       tools/emulator/arena_simulation.cpp tools/emulator/robot_memory.cpp \
                       tools/emulator/sound_field.cpp tools/emulator/battery.cpp \
                       tools/emulator/remote_control.cpp tools/emulator/arena_control.cpp \
                       tools/emulator/control_port.cpp \
                       tools/emulator/arena_feed.cpp

# epuck-emu: the e-puck firmware image running on a PC.
PROGRAMS += epuck-emu
epuck-emu_SOURCES := tools/emulator/epuck_emu.cpp
epuck-emu_LIBS := aseba_dspic30_robot dspic30_sim aseba_arena aseba_emulator_network aseba_host_robot aseba_flash aseba_firmware \
                  aseba_epuck aseba_store aseba_bootloader aseba_host_board aseba_compiler aseba_node \
                  aseba_vm aseba_natives
epuck-emu_LDLIBS := -lenki -pthread

# An e-puck of the arena on the simulated dsPIC30F6014A (tools/dspic30_sim):
# the board around the chip fed by the robot's world, and the camera's
# pixel port on the chip's clock.
LIBRARIES += aseba_dspic30_robot
aseba_dspic30_robot_SOURCES := tools/emulator/dspic30_robot.cpp tools/emulator/dspic30_pixel_port.cpp \
                               tools/emulator/dspic30_arena.cpp
