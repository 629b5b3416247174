# dspic30_sim: an instruction-set simulator of the e-puck's dsPIC30F6014A
# (docs/dspic30-sim.md): the instruction table (instructions.def), the
# decoder and disassembler driven by it, and the executor.
LIBRARIES += dspic30_sim
dspic30_sim_SOURCES := tools/dspic30_sim/isa.cpp tools/dspic30_sim/disassembler.cpp \
                       tools/dspic30_sim/predecode.cpp tools/dspic30_sim/program_memory.cpp \
                       tools/dspic30_sim/cpu.cpp tools/dspic30_sim/cpu_memory.cpp \
                       tools/dspic30_sim/cpu_execute.cpp tools/dspic30_sim/cpu_dsp.cpp \
                       tools/dspic30_sim/cpu_exceptions.cpp tools/dspic30_sim/cpu_nvm.cpp \
                       tools/dspic30_sim/uart.cpp tools/dspic30_sim/timers.cpp \
                       tools/dspic30_sim/gpio.cpp tools/dspic30_sim/adc.cpp \
                       tools/dspic30_sim/i2c.cpp \
                       tools/dspic30_sim/intel_hex.cpp tools/dspic30_sim/memory_file.cpp \
                       tools/dspic30_sim/tcp_link.cpp \
                       tools/dspic30_sim/simulator.cpp

# dspic30-sim: runs an image, UART1 on standard input and output.
PROGRAMS += dspic30-sim
dspic30-sim_SOURCES := tools/dspic30_sim/dspic30_sim_main.cpp
dspic30-sim_LIBS := dspic30_sim

# Microchip's pic30-elf toolchain (binutils and GCC 4.5.1, built from XC16's
# GPL sources), which `scripts/install-deps.sh dspic30` unpacks into the
# build folder (the same as `make dspic30`'s): the tests' oracle
# (pic30-elf-objdump) and the compiler of their programs.
# (tests/dspic30_sim/module.mk, read first, names the same folder.)
PIC30_BIN ?= $(BUILD)/toolchains/pic30-elf/bin
PIC30_TOOLCHAIN ?= $(PIC30_BIN)/pic30-elf-gcc
$(PIC30_TOOLCHAIN): | $(BUILD)/.deps-dspic30
	@test -x $@ || { echo "dspic30_sim: no pic30-elf toolchain in $(PIC30_BIN)"; exit 1; }
