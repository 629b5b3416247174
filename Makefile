# One non-recursive build for the whole project. Each folder describes its
# libraries, programs and tests in a module.mk; this file turns them into
# rules for every build variant, out of tree under build/<variant>/.
#
#   make               everything for the host (build/host)
#   make test          every test, under ASan + UBSan (build/host-sanitize)
#   make cross-check   the portable layers with 16- and 32-bit cross compilers
#   make fuzz          every fuzz target for FUZZ_SECONDS (default 60) each
#   make bench         performance figures beside the reference (docs/benchmarks.md)
#   make dspic30       the e-puck's images, with XC16 or a pic30-elf GCC (ports/dspic30/module.mk)
#   make stm32f4       the STM32F4 image, run by QEMU in the tests (ports/stm32f4/module.mk)
#   make run           the main job
#   make install       the programs in PREFIX/bin (default /usr/local)
#   make format        clang-format every C and C++ file (make test checks it)

.DEFAULT_GOAL := all
SHELL := /bin/bash
MAKEFLAGS += -j$(shell nproc 2>/dev/null || echo 2)
BUILD ?= build

CC := gcc
CXX := g++

WARNINGS := -Wall -Wextra -Werror -Wshadow -Wpointer-arith -Wundef
C_STANDARD := -std=gnu99
CXX_STANDARD := -std=c++20
# Standalone asio (not Boost's), one way in every file: its aligned
# allocation would otherwise depend on which standard headers a file
# includes first, and memory allocated in one file could be freed with the
# wrong function in another.
CXX_DEFINES := -DASIO_STANDALONE -DASIO_DISABLE_STD_ALIGNED_ALLOC
INCLUDES := -I. -Ivm -Inative_functions
# Every build names its target's one configuration header (docs/porting.md);
# the host variants are the host target, the simulated e-puck.
HOST_TARGET_CONFIG := '-DTARGET_CONFIG="boards/epuck_host/epuck_host_config.h"'
INCLUDES += $(HOST_TARGET_CONFIG)

# Build variants: the plain host build, and the one the tests run in.
# Line tables (-g1) are what a backtrace, a profiler or a sanitizer's
# report prints, for two thirds of the compile time of full debug
# information (`make host_FLAGS='-O0 -g'` for a debugger's build).
# The plain build is optimised at link time: the firmware's layers call
# each other across files (the board, the devices, the main loop, the VM),
# which only the linker can inline; the arena at 100 robots runs 11% fewer
# host instructions so, and `make run` builds in the same time.
VARIANTS := host host-sanitize
host_FLAGS := -O2 -g1 -flto=auto
SANITIZE := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
host-sanitize_FLAGS := -O1 -g1 $(SANITIZE)

LIBRARIES :=
PROGRAMS :=
TESTS :=
PLAIN_TESTS :=
# Tests that are not GoogleTest programs (the IDE's browser tests): any
# program whose output ends with "N passed, N failed".
TEST_SCRIPTS :=

# --- dependencies from Debian, installed once by the project's script ------
# (defined before the modules, whose rules name them)
# One stamp per group of scripts/install-deps.sh: `make` and `make run` need
# the small build group only; the reference Aseba (an oracle with large GUI
# dependencies) comes with the groups of the targets that use it.
DEPS_STAMP := $(BUILD)/.deps-build
TEST_DEPS_STAMP := $(BUILD)/.deps-test
CROSS_DEPS_STAMP := $(BUILD)/.deps-cross
FUZZ_DEPS_STAMP := $(BUILD)/.deps-fuzz
BENCH_DEPS_STAMP := $(BUILD)/.deps-bench
EXPERIMENT_DEPS_STAMP := $(BUILD)/.deps-experiment

include $(sort $(wildcard */module.mk */*/module.mk */*/*/module.mk))

$(BUILD)/.deps-%: scripts/install-deps.sh
	@BUILD=$(BUILD) scripts/install-deps.sh $*
	@mkdir -p $(@D) && touch $@

# --- per-variant rules -----------------------------------------------------
# $(1) = variant. Objects mirror the source tree under build/<variant>/obj.
define VARIANT_RULES
$(BUILD)/$(1)/obj/%.o: %.c | $(DEPS_STAMP)
	@mkdir -p $$(@D)
	$$(CC) $(C_STANDARD) $(WARNINGS) $$($(1)_FLAGS) $$(INCLUDES) $$(EXTRA_CFLAGS_$$*) -MMD -MP -c $$< -o $$@

$(BUILD)/$(1)/obj/%.o: %.cpp | $(DEPS_STAMP)
	@mkdir -p $$(@D)
	$$(CXX) $(CXX_STANDARD) $(CXX_DEFINES) $(WARNINGS) $$($(1)_FLAGS) $$($(1)_CXXFLAGS) $$(INCLUDES) $$(EXTRA_CFLAGS_$$*) -MMD -MP -c $$< -o $$@
endef
$(foreach v,$(VARIANTS),$(eval $(call VARIANT_RULES,$(v))))
# Building the tests is most of `make test`'s time: the code under test is
# optimised as ASan's authors advise, with line tables only (what its
# reports print), and checked by both sanitizers in full. The tests' own
# files, mostly GoogleTest's macros, are not optimised (half their compile
# time), not checked for dynamic types (UBSan's vptr check on GoogleTest's
# own classes: a third of what is left), and include GoogleTest's header
# precompiled once (a fifth of what is left).
TEST_SANITIZE := $(SANITIZE) -fno-sanitize=vptr
TEST_PRELUDE := $(BUILD)/host-sanitize/pch/test_prelude.hpp
$(BUILD)/host-sanitize/obj/tests/%.o: host-sanitize_FLAGS = -O0 -g1 $(TEST_SANITIZE)
$(BUILD)/host-sanitize/obj/tests/%.o: host-sanitize_CXXFLAGS = -include $(TEST_PRELUDE)
# The tools whose tests wait on sockets, a broker and a browser rather than
# on their code (the console, the client library, the IDE's and the MQTT
# bridge's servers) are optimised for debugging instead: with the
# sanitizers, -Og compiles their asio, websocketpp and JSON templates in a
# third less time than -O1 (95 of 325 processor seconds here).
SANITIZED_AT_OG := console client ide mqtt
$(foreach t,$(SANITIZED_AT_OG),$(BUILD)/host-sanitize/obj/tools/$(t)/%.o): \
    host-sanitize_FLAGS = -Og -g1 $(SANITIZE)
# GCC takes the .gch beside the header named by -include when it was built
# with the same options, and the header itself otherwise.
$(TEST_PRELUDE).gch: tests/test_prelude.hpp | $(TEST_DEPS_STAMP)
	@mkdir -p $(@D)
	cp $< $(TEST_PRELUDE)
	$(CXX) $(CXX_STANDARD) $(CXX_DEFINES) $(WARNINGS) -O0 -g1 $(TEST_SANITIZE) $(INCLUDES) -x c++-header $< -o $@

objects = $(patsubst %,$(BUILD)/$(1)/obj/%.o,$(basename $(2)))

# $(1) = variant, $(2) = library name: build/<variant>/lib/lib<name>.a
define LIBRARY_RULES
$(BUILD)/$(1)/lib/lib$(2).a: $(call objects,$(1),$($(2)_SOURCES))
	@mkdir -p $$(@D)
	@rm -f $$@
	ar rcs $$@ $$^
endef

# $(1) = variant, $(2) = program, $(3) = output folder (bin or tests).
# A program lists its own sources, the project libraries it uses (in link
# order) and any system libraries; a project library names the system
# libraries it needs itself (NAME_LDLIBS), added to every program using it.
define PROGRAM_RULES
$(BUILD)/$(1)/$(3)/$(2): $(call objects,$(1),$($(2)_SOURCES)) \
                         $(foreach l,$($(2)_LIBS),$(BUILD)/$(1)/lib/lib$(l).a)
	@mkdir -p $$(@D)
	$$(CXX) $$($(1)_FLAGS) $$^ $$($(2)_LDLIBS) $(sort $(foreach l,$($(2)_LIBS),$($(l)_LDLIBS))) -o $$@
endef

$(foreach v,$(VARIANTS),$(foreach l,$(LIBRARIES),$(eval $(call LIBRARY_RULES,$(v),$(l)))))
$(foreach v,$(VARIANTS),$(foreach p,$(PROGRAMS),$(eval $(call PROGRAM_RULES,$(v),$(p),bin))))
$(foreach v,$(VARIANTS),$(foreach t,$(TESTS),$(eval $(call PROGRAM_RULES,$(v),$(t),tests))))

# Tests and benchmark programs compile against GoogleTest and the
# reference's headers and libraries. Only their own files wait for those:
# a product source that a test also compiles is built by `make run` too,
# which must not install the test group.
own_files = $(filter tests/% bench/%,$(1))
$(foreach v,$(VARIANTS),$(foreach t,$(TESTS),\
  $(eval $(call objects,$(v),$(call own_files,$($(t)_SOURCES))) $(BUILD)/$(v)/tests/$(t): | $(TEST_DEPS_STAMP))))
$(foreach v,$(VARIANTS),$(foreach p,$(filter bench-%,$(PROGRAMS)),\
  $(eval $(call objects,$(v),$(call own_files,$($(p)_SOURCES))) $(BUILD)/$(v)/bin/$(p): | $(TEST_DEPS_STAMP))))

ALL_SOURCES := $(sort $(foreach x,$(LIBRARIES) $(PROGRAMS) $(TESTS),$($(x)_SOURCES)))
# Every C++ file under tests/ that the sanitized build compiles (tests,
# their support libraries, benchmarks) includes the precompiled header.
$(eval $(call objects,host-sanitize,$(filter tests/%.cpp,$(ALL_SOURCES))): $(TEST_PRELUDE).gch)
-include $(patsubst %.o,%.d,$(foreach v,$(VARIANTS),$(call objects,$(v),$(ALL_SOURCES))))

# --- top-level targets -----------------------------------------------------
HOST_OUTPUTS = $(foreach l,$(LIBRARIES),$(BUILD)/host/lib/lib$(l).a) \
               $(foreach p,$(PROGRAMS),$(BUILD)/host/bin/$(p)) \
               $(foreach t,$(TESTS),$(BUILD)/host/tests/$(t))
# Every test under ASan and UBSan, but PLAIN_TESTS: those whose subject is
# the dsPIC's machine code on the simulator, where the sanitizers would only
# slow the simulator down (they run in the plain build).
TEST_BINARIES = $(foreach t,$(filter-out $(PLAIN_TESTS),$(TESTS)),$(BUILD)/host-sanitize/tests/$(t)) \
                $(foreach t,$(PLAIN_TESTS),$(BUILD)/host/tests/$(t))

.PHONY: all test tests cross-check run format clean deps fuzz bench install
all: $(HOST_OUTPUTS)

tests: $(TEST_BINARIES) $(TEST_SCRIPTS)

# The longest programs start first, so that none is left running alone at
# the end (the browser tests take three minutes, the console's one and a half).
LONGEST_TESTS = $(IDE_BROWSER_TEST) $(BUILD)/host-sanitize/tests/console_test
test: $(TEST_BINARIES) $(TEST_SCRIPTS)
	@scripts/run-tests.sh $(LONGEST_TESTS) $(filter-out $(LONGEST_TESTS),$(TEST_BINARIES) $(TEST_SCRIPTS))

deps:
	@scripts/install-deps.sh build test cross fuzz bench experiment

# The portable layers must build warning-free where `int` is 16 bits (the
# dsPIC's case, here avr-gcc) and on a 32-bit microcontroller; they are
# compiled with the e-puck target's configuration (scripts/cross-check.sh).
PORTABLE_SOURCES := $(wildcard vm/*.c native_functions/*.c store/*.c bootloader/*.c firmware/*.c \
                                robots/*/*.c robots/*/devices/*.c)
dspic30-check: | $(CROSS_DEPS_STAMP)
cross-check: | $(CROSS_DEPS_STAMP)
	@scripts/cross-check.sh $(BUILD) $(PORTABLE_SOURCES)

# The sources of a library or program, for scripts that build it another way
# (fuzzing with clang): `make -s sources-aseba_natives`.
sources-%:
	@echo $($*_SOURCES)

# A variable of this Makefile, for the same scripts: `make -s print-CXX_DEFINES`.
print-%:
	@echo $($*)

# Every libFuzzer target for FUZZ_SECONDS each, under ASan + UBSan.
FUZZ_SECONDS ?= 60
fuzz: | $(FUZZ_DEPS_STAMP)
	+@scripts/fuzz.sh $(FUZZ_SECONDS) $(BUILD)

# Performance figures beside the reference Aseba: one table, also written to
# docs/benchmarks.md (see scripts/bench.sh). `+`: the script's own make
# calls share this make's job slots (else they build one file at a time).
bench: $(DSPIC30_OUT)/epuck-aseba.hex | $(DEPS_STAMP) $(TEST_DEPS_STAMP) $(BENCH_DEPS_STAMP)
	+@scripts/bench.sh $(BUILD)

# The main job; RUN_ARGS go to epuck-emu (e.g. RUN_ARGS="--duration 60").
# It builds the programs a user runs beside it, and needs the build group of
# dependencies only.
run: $(BUILD)/host/bin/epuck-emu $(BUILD)/host/bin/aseba-ide $(BUILD)/host/bin/aseba $(BUILD)/host/bin/asebac
	@scripts/run-main-job.sh $(BUILD)/host $(RUN_ARGS)

# The programs a user runs, on the PATH: `make install PREFIX=~/.local`.
PREFIX ?= /usr/local
INSTALLED_PROGRAMS := aseba aseba-ide aseba-mqtt asebac epuck-emu epuck-image
install: $(foreach p,$(INSTALLED_PROGRAMS),$(BUILD)/host/bin/$(p))
	install -d $(DESTDIR)$(PREFIX)/bin
	install -m 755 $^ $(DESTDIR)$(PREFIX)/bin/
	@echo "installed $(INSTALLED_PROGRAMS) in $(DESTDIR)$(PREFIX)/bin"

format: | $(TEST_DEPS_STAMP)
	@scripts/check-format.sh --apply

clean:
	rm -rf $(BUILD)
