# Benchmark programs, run by `make bench` (scripts/bench.sh) in the plain host
# build. They link Debian's reference libraries (libasebavm, libasebacompiler)
# to measure the reference in the same run; the reference is only measured.
BENCH_COMPILER_LIBS := aseba_compiler aseba_natives

# The VM dispatch loop, once per dispatch variant of our VM; the reference VM
# is linked in both (its symbols are AsebaVM*, ours vm_*).
BENCH_VM_SOURCES := bench/vm_bench.cpp tests/vm/reference_node.cpp
PROGRAMS += bench-vm
bench-vm_SOURCES := $(BENCH_VM_SOURCES)
bench-vm_LIBS := test_support $(BENCH_COMPILER_LIBS) aseba_vm
bench-vm_LDLIBS := -lasebavm

PROGRAMS += bench-vm-goto
bench-vm-goto_SOURCES := $(BENCH_VM_SOURCES)
bench-vm-goto_LIBS := test_support $(BENCH_COMPILER_LIBS) aseba_vm_goto
bench-vm-goto_LDLIBS := -lasebavm

# The compiler against the reference compiler on the same inputs.
PROGRAMS += bench-compiler
bench-compiler_SOURCES := bench/compiler_bench.cpp tests/compiler/reference_oracle.cpp \
                          tests/compiler/reference_containment.cpp
bench-compiler_LIBS := $(BENCH_COMPILER_LIBS) aseba_vm
bench-compiler_LDLIBS := -lasebacompiler -lasebacommon

# The node over loopback TCP (epuck-emu against asebadummynode) and the
# simulator's CPU cost per robot; epuck-emu is run, not linked.
PROGRAMS += bench-node
bench-node_SOURCES := bench/node_bench.cpp tests/interop/child_process.cpp \
                      tests/interop/interop_support.cpp
bench-node_LIBS := aseba_client $(BENCH_COMPILER_LIBS) aseba_vm

# The tools and the simulated network under load (edit to running on six
# robots, bursts of connections, a flood); epuck-emu and aseba are run, not
# linked.
PROGRAMS += bench-network
bench-network_SOURCES := bench/network_bench.cpp tests/interop/child_process.cpp \
                         tests/interop/interop_support.cpp
bench-network_LIBS := aseba_client $(BENCH_COMPILER_LIBS) aseba_vm
$(foreach v,$(VARIANTS),$(eval \
  $(BUILD)/$(v)/bin/bench-network: | $(BUILD)/$(v)/bin/epuck-emu $(BUILD)/$(v)/bin/aseba))
