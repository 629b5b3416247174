# Benchmark programs, run by `make bench` (scripts/bench.sh) in the plain host
# build. They link Debian's reference libraries (libasebavm, libasebacompiler)
# to measure the reference in the same run; the reference is only measured.
BENCH_COMPILER_LIBS := aseba_compiler aseba_natives

# The VM dispatch loop, once per dispatch variant of our VM (bench-vm: as the
# host tools use it, computed goto; bench-vm-switch: the dsPIC's switch); the
# reference VM is linked in both (its symbols are AsebaVM*, ours vm_*).
BENCH_VM_SOURCES := bench/vm_bench.cpp tests/vm/reference_node.cpp
PROGRAMS += bench-vm
bench-vm_SOURCES := $(BENCH_VM_SOURCES)
bench-vm_LIBS := test_support $(BENCH_COMPILER_LIBS) aseba_vm
bench-vm_LDLIBS := -lasebavm

PROGRAMS += bench-vm-switch
bench-vm-switch_SOURCES := $(BENCH_VM_SOURCES)
bench-vm-switch_LIBS := test_support $(BENCH_COMPILER_LIBS) aseba_vm_switch
bench-vm-switch_LDLIBS := -lasebavm

# The compiler against the reference compiler on the same inputs.
PROGRAMS += bench-compiler
bench-compiler_SOURCES := bench/compiler_bench.cpp tests/compiler/reference_oracle.cpp \
                          tests/compiler/reference_containment.cpp
bench-compiler_LIBS := $(BENCH_COMPILER_LIBS) aseba_vm
bench-compiler_LDLIBS := -lasebacompiler -lasebacommon

# The reference compiler as a process (Debian has no compiler command), for
# the whole-process figure: bench-compiler runs it beside asebac.
PROGRAMS += bench-reference-compile
bench-reference-compile_SOURCES := bench/reference_compile.cpp tests/compiler/reference_oracle.cpp \
                                   tests/compiler/reference_containment.cpp
bench-reference-compile_LIBS := $(BENCH_COMPILER_LIBS) aseba_vm
bench-reference-compile_LDLIBS := -lasebacompiler -lasebacommon

# The node over loopback TCP (epuck-emu against asebadummynode) and the
# simulator's CPU cost per robot; epuck-emu is run, not linked.
PROGRAMS += bench-node
bench-node_SOURCES := bench/node_bench.cpp tests/interop/child_process.cpp \
                      tests/interop/interop_support.cpp
bench-node_LIBS := aseba_client $(BENCH_COMPILER_LIBS) aseba_vm

# The VM on a 16-bit-int AVR: simavr runs bench/avr_workload.c (which
# scripts/bench.sh builds with avr-gcc) and this counts its instructions.
PROGRAMS += avr-step-counter
avr-step-counter_SOURCES := bench/avr_step_counter.c
avr-step-counter_LDLIBS := -lsimavr
# simavr's header and library come with the bench group, which `make` (whose
# default goal builds this program) installs too.
$(foreach v,$(VARIANTS),$(eval $(BUILD)/$(v)/obj/bench/avr_step_counter.o: | $(BENCH_DEPS_STAMP)))

# `make cross-check` also prints the RAM of the e-puck firmware, measured on
# a linked 16-bit image (bench/firmware_ram.sh; `make bench` gives its parts).
.PHONY: firmware-ram
firmware-ram: | $(DEPS_STAMP) $(CROSS_DEPS_STAMP)
	@ram=$$(bench/firmware_ram.sh $(BUILD)) && echo "$$ram" | awk '$$1 == "total" { \
	    printf "== e-puck firmware, linked 16-bit image (avr-gcc): %d bytes of RAM\n", $$2 }'
cross-check: firmware-ram

# The tools and the simulated network under load (edit to running on six
# robots, bursts of connections, a flood); epuck-emu and aseba are run, not
# linked.
PROGRAMS += bench-network
bench-network_SOURCES := bench/network_bench.cpp tests/interop/child_process.cpp \
                         tests/interop/interop_support.cpp
bench-network_LIBS := aseba_client $(BENCH_COMPILER_LIBS) aseba_vm
$(foreach v,$(VARIANTS),$(eval \
  $(BUILD)/$(v)/bin/bench-network: | $(BUILD)/$(v)/bin/epuck-emu $(BUILD)/$(v)/bin/aseba))

# The MQTT bridge: event latency from a robot of one network to a robot of
# another through two bridges and mosquitto, and the events per second one
# bridge publishes; mosquitto, epuck-emu and aseba-mqtt are run, not linked.
PROGRAMS += bench-mqtt
bench-mqtt_SOURCES := bench/mqtt_bench.cpp tests/mqtt/mqtt_support.cpp \
                      tests/console/console_support.cpp
bench-mqtt_LIBS := aseba_mqtt aseba_client aseba_compiler aseba_node
$(foreach v,$(VARIANTS),$(eval \
  $(BUILD)/$(v)/bin/bench-mqtt: | $(BUILD)/$(v)/bin/epuck-emu $(BUILD)/$(v)/bin/aseba-mqtt))

# The dsPIC30F simulator's speed (tools/dspic30_sim): bench/dspic30_workload.c
# built for the dsPIC30F6014A with the pic30-elf toolchain on the port's
# start-up, as the bare programs of tests/dspic30_sim are
# (tests/dspic30_sim/module.mk).
DSPIC30_BENCH_OUT := $(BUILD)/dspic30_sim/bench
DSPIC30_WORKLOAD := $(DSPIC30_BENCH_OUT)/dspic30_workload.hex
DSPIC30_BENCH_SUPPORT := $(addprefix $(BUILD)/dspic30_sim/torture/support/,dspic30_reset.o \
                           dspic30_startup.o dspic30_runtime.o)
$(DSPIC30_WORKLOAD): bench/dspic30_workload.c $(DSPIC30_BENCH_SUPPORT) \
                     tests/dspic30_sim/runtime/bare_chip.gld tests/dspic30_sim/runtime/torture_p30f6014a.gld
	@mkdir -p $(@D)
	$(PIC30_BIN)/pic30-elf-gcc $(PIC30_CFLAGS) -std=gnu99 -ffreestanding $(PIC30_GCC_INCLUDES) -c $< \
	    -o $(@:.hex=.o)
	$(call PIC30_LINK,$(@:.hex=.elf),$(DSPIC30_BENCH_SUPPORT) $(@:.hex=.o))
	$(PIC30_BIN)/pic30-elf-bin2hex $(@:.hex=.elf)

PROGRAMS += bench-dspic30-sim
bench-dspic30-sim_SOURCES := bench/dspic30_sim_bench.cpp
bench-dspic30-sim_LIBS := dspic30_sim
EXTRA_CFLAGS_bench/dspic30_sim_bench := '-DDSPIC30_WORKLOAD="$(DSPIC30_WORKLOAD)"'
$(foreach v,$(VARIANTS),$(eval $(BUILD)/$(v)/bin/bench-dspic30-sim: | $(DSPIC30_WORKLOAD)))
