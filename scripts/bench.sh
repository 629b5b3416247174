#!/usr/bin/env bash
# `make bench`: builds the benchmark programs of bench/ in the plain host
# build, measures our VM, code size, compiler, node and simulator beside the
# reference Aseba (Debian's `aseba`) in the same run, and prints one table,
# also written to docs/benchmarks.md (replaced on every run).
# Usage: scripts/bench.sh BUILD_DIR       (run from the repository root)
set -euo pipefail
build=$1
bin=$build/host/bin
report=docs/benchmarks.md
# The machine's load when the run starts and ends: timed figures mean
# little on a machine busy with other work, and the reader must know.
load_at_start=$(cut -d' ' -f1 /proc/loadavg)

# Repetitions, kept small enough for the whole run to take a few minutes.
vm_timing_runs=30
compiler_runs=20
compiler_process_runs=40
simulator_seconds=5
simulator_robots_many=1000 # epuck-emu's maximum
paper_budget_bytes=10240   # the 2007 paper's budget for VM + natives + protocol
avr_aim_bytes=8192
vm_goal_instructions=18
ram_goal_bytes=4096 # the paper's RAM for the e-puck firmware
node_goal_ratio=1.5 # user events per second, over the reference's
compiler_goal_ratio=0.8 # compile time, over the reference's

echo "bench: building" >&2
make --no-print-directory BUILD="$build" "$bin/bench-vm" "$bin/bench-vm-switch" \
    "$bin/avr-step-counter" "$bin/bench-compiler" "$bin/bench-reference-compile" "$bin/asebac" \
    "$bin/bench-node" "$bin/bench-dsp" \
    "$bin/bench-dspic30-sim" "$bin/dspic30-sim" "$bin/aseba" \
    "$bin/epuck-emu" >&2

ratio() { awk -v a="$1" -v b="$2" 'BEGIN { if (b + 0 == 0) print "-"; else printf "%.2f", a / b }'; }
divide() { awk -v a="$1" -v b="$2" -v f="$3" 'BEGIN { printf f, a / b }'; }

# --- VM dispatch -----------------------------------------------------------
# bench-vm is the VM as the host tools build it (computed goto);
# bench-vm-switch the switch dispatch that the dsPIC build uses.
echo "bench: VM (callgrind)" >&2
steps=$("$bin/bench-vm" steps ours) # also checks that both VMs agree
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# Host instructions executed inside the run function, setup excluded; the
# function's copies that the link-time optimiser specialises
# (vm_run.constprop.0) count as the function.
instructions() { # program vm function
    valgrind --tool=callgrind --toggle-collect="$3" --toggle-collect="$3.*" \
        --callgrind-out-file="$scratch/out" \
        "$bin/$1" once "$2" 2>"$scratch/log" >/dev/null
    collected "$3"
}
# What callgrind counted, which a function renamed by the compiler would
# leave at zero: that stops the run rather than print a figure of 0.
collected() { # function
    local count
    count=$(awk '/Collected :/ { print $NF }' "$scratch/log")
    if [ "${count:-0}" -le 0 ]; then
        echo "bench: callgrind counted no instruction in $1" >&2
        exit 1
    fi
    echo "$count"
}
# Host instructions of one call of a DSP native (bench-dsp WHICH).
instructions_of_native() { # which function
    valgrind --tool=callgrind --toggle-collect="$2" --toggle-collect="$2.*" \
        --callgrind-out-file="$scratch/out" \
        "$bin/bench-dsp" "$1" 2>"$scratch/log" >/dev/null
    collected "$2"
}
ir_shipped=$(instructions bench-vm ours vm_run)
ir_switch=$(instructions bench-vm-switch ours vm_run)
ir_reference=$(instructions bench-vm reference AsebaVMRun)
per_step_shipped=$(divide "$ir_shipped" "$steps" %.1f)
per_step_switch=$(divide "$ir_switch" "$steps" %.1f)
per_step_reference=$(divide "$ir_reference" "$steps" %.1f)

echo "bench: VM (wall clock)" >&2
ns_shipped=$(divide "$("$bin/bench-vm" time ours $vm_timing_runs)" "$steps" %.2f)
ns_switch=$(divide "$("$bin/bench-vm-switch" time ours $vm_timing_runs)" "$steps" %.2f)
ns_reference=$(divide "$("$bin/bench-vm" time reference $vm_timing_runs)" "$steps" %.2f)

# --- VM on a 16-bit-int AVR (simavr), a proxy for the dsPIC -------------------
# The same workload's bytecode (bench-vm header) in bench/avr_workload.c,
# built with avr-gcc -Os in both dispatch variants; avr-step-counter counts
# the AVR instructions and cycles of event `go` and the checksum of the
# variables, which must be the host's.
echo "bench: VM on the AVR (simavr)" >&2
# The dsPIC target's switches, for what stands for the dsPIC (the dispatch
# given on top).
dspic30_config=('-DTARGET_CONFIG="boards/epuck_dspic30/epuck_dspic30_config.h"')
"$bin/bench-vm" header >"$scratch/workload.h"
host_checksum=$("$bin/bench-vm" checksum ours)
avr_vm() { # dispatch (0: switch, 1: computed goto) -> "instructions cycles"
    avr-gcc -std=gnu99 -Os -mmcu=atmega1284p -I. -Ivm -Inative_functions "${dspic30_config[@]}" \
        -DVM_USE_COMPUTED_GOTO="$1" "-DVM_WORKLOAD_HEADER=\"$scratch/workload.h\"" \
        -ffunction-sections -fdata-sections -Wl,--gc-sections bench/avr_workload.c \
        vm/vm.c vm/vm_debug.c vm/vm_verify.c -o "$scratch/avr-$1.elf"
    local instructions cycles checksum
    # simavr prints its own lines first: the counts are the last one.
    read -r instructions cycles checksum < <("$bin/avr-step-counter" "$scratch/avr-$1.elf" | tail -n 1)
    if [ "$checksum" != "$host_checksum" ]; then
        echo "bench: the AVR run of the workload ended with other variables" >&2
        exit 1
    fi
    echo "$(divide "$instructions" "$steps" %.1f) $(divide "$cycles" "$steps" %.1f)"
}
read -r avr_instructions_switch avr_cycles_switch < <(avr_vm 0)
read -r avr_instructions_goto avr_cycles_goto < <(avr_vm 1)

# --- code size -------------------------------------------------------------
echo "bench: code size" >&2
# The standard natives only (native_functions/ also holds optional ones).
standard_natives=(native_functions/nat_arguments.c native_functions/nat_math.c
                  native_functions/nat_trigonometry.c native_functions/nat_deque.c
                  native_functions/nat_standard.c)
sizes=$(scripts/cross-check.sh "$build/bench" vm/*.c "${standard_natives[@]}")
# From the N-th "linked image" line (1: avr, 2: arm): its code, and its code
# plus constant data (what the flash must hold).
linked_of() { # n field(1: code, 2: code + constant)
    echo "$sizes" | awk -v n="$1" -v field="$2" '/linked image/ {
        seen++
        if (seen != n) next
        gsub(/[^0-9]+/, " ")
        split($0, numbers, " ")
        print field == 1 ? numbers[1] : numbers[1] + numbers[2]
    }'
}
avr_flash=$(linked_of 1 2)
arm_flash=$(linked_of 2 2)
avr_code=$(linked_of 1 1)
arm_code=$(linked_of 2 1)
if [ -z "$avr_flash" ] || [ -z "$arm_flash" ]; then
    echo "bench: cross-check.sh printed no linked image sizes" >&2
    exit 1
fi

# --- RAM of the e-puck firmware ------------------------------------------------
echo "bench: firmware RAM" >&2
ram=$(bench/firmware_ram.sh "$build")
ram_of() { echo "$ram" | awk -v name="$1" '$1 == name { print $2 }'; }
ram_total=$(ram_of total)
ram_vm_memory=$(($(ram_of vm_bytecode) + $(ram_of vm_variables) + $(ram_of vm_stack)))
ram_node=$(ram_of node_state)
ram_frame=$(ram_of node_receive_frame)
ram_board=$(ram_of board)
ram_loop=$(($(ram_of firmware) - ram_vm_memory - ram_node))
ram_devices=$(ram_of robot_devices)
ram_other=$((ram_total - $(ram_of firmware) - ram_board - ram_devices))

# --- the dsPIC30 images, linked (make dspic30) ---------------------------------
echo "bench: dsPIC30 images" >&2
dspic=$(bench/dspic30_sizes.py "$build" "$(MAKEFLAGS= make -s --no-print-directory print-DSPIC_PREFIX)")
dspic_of() { echo "$dspic" | awk -v name="$1" '$1 == name { print $2 }'; }
bytes_of_words() { echo $(($1 * 3)); } # the paper's unit: 3 bytes per instruction word
dspic_core_code=$(($(dspic_of code_vm) + $(dspic_of code_natives) + $(dspic_of code_node)))
dspic_core_const=$(($(dspic_of const_vm) + $(dspic_of const_natives) + $(dspic_of const_node)))
dspic_core_bytes=$(bytes_of_words $((dspic_core_code + dspic_core_const)))
dspic_ram_total=$(dspic_of ram_total)
dspic_ram_vm=$(($(dspic_of vm_bytecode) + $(dspic_of vm_variables) + $(dspic_of vm_stack)))
dspic_ram_node=$(dspic_of node_state)
dspic_ram_loop=$(($(dspic_of firmware) - dspic_ram_vm - dspic_ram_node))
dspic_ram_other=$((dspic_ram_total - $(dspic_of firmware) - $(dspic_of board) - $(dspic_of robot_devices)))
dspic_parts=""
for part in vm node natives dsp_natives firmware drivers store port runtime other; do
    dspic_parts+="${dspic_parts:+, }$part $(dspic_of code_$part)+$(dspic_of const_$part)"
done

# --- compiler --------------------------------------------------------------
echo "bench: compiler" >&2
compiler=$("$bin/bench-compiler" $compiler_runs)
compiler_field() { echo "$compiler" | awk -F'\t' -v name="$1" -v f="$2" '$1 == name { print $f }'; }
read -r _ process_ours process_reference < <("$bin/bench-compiler" processes $compiler_process_runs)

# --- DSP natives -------------------------------------------------------------
echo "bench: DSP natives" >&2
fft_instructions=$(instructions_of_native fft nat_dsp_fft_function)
fir_instructions=$(instructions_of_native fir nat_dsp_fir_function)
dsp_avr_code=0
for source in native_functions/nat_dsp*.c; do
    # nat_dsp_dspic30.c needs XC16's DSP builtins; the portable kernel stands for it.
    [[ $source == *_dspic30.c ]] && continue
    avr-gcc -std=gnu99 -Os -mmcu=atmega1284p -ffunction-sections -I. -Ivm -Inative_functions \
        "${dspic30_config[@]}" -c "$source" -o "$scratch/dsp.o"
    code=$(avr-size -A "$scratch/dsp.o" | awk '$1 ~ /^\.text/ { c += $2 } END { print c + 0 }')
    dsp_avr_code=$((dsp_avr_code + code))
done

# --- node and simulator ----------------------------------------------------
echo "bench: node" >&2
# The median of several runs of each node, interleaved: one run of either
# moves by a third from one minute to the next on a shared machine (the
# spinning client and the node keep both of its cores busy: whatever else
# runs takes from them), the median much less.
median_of() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
node_runs=5
node_run_events=100000
: >"$scratch/node-ours"
: >"$scratch/node-reference"
: >"$scratch/node-at-once"
for _ in $(seq $node_runs); do
    "$bin/bench-node" emu $node_run_events >>"$scratch/node-ours"
    "$bin/bench-node" reference $node_run_events >>"$scratch/node-reference"
    "$bin/bench-node" at-once $node_run_events >>"$scratch/node-at-once"
done
column_median() { cut -f"$1" "$2" | median_of; } # column file
ours_latency_median=$(column_median 1 "$scratch/node-ours")
ours_latency_mean=$(column_median 2 "$scratch/node-ours")
ours_events=$(column_median 3 "$scratch/node-ours")
ref_latency_median=$(column_median 1 "$scratch/node-reference")
ref_latency_mean=$(column_median 2 "$scratch/node-reference")
ref_events=$(column_median 3 "$scratch/node-reference")
column_range() { cut -f"$1" "$2" | sort -n | sed -n '1p;$p' | paste -sd'-'; } # column file
ours_events_range=$(column_range 3 "$scratch/node-ours")
ref_events_range=$(column_range 3 "$scratch/node-reference")
at_once_events=$(column_median 3 "$scratch/node-at-once")
at_once_events_range=$(column_range 3 "$scratch/node-at-once")
# Host instructions per user event: the node's whole process under
# callgrind, the difference between runs of 20,000 and 60,000 events over
# the 40,000 more (start-up, loading and the GET_VARIABLES rounds cancel);
# the median of three such pairs, as the events a read brings vary.
node_run_instructions() { # emu|reference events
    BENCH_NODE_UNDER="valgrind --tool=callgrind --callgrind-out-file=$scratch/node.out" \
        "$bin/bench-node" "$1" "$2" >/dev/null
    callgrind_annotate "$scratch/node.out" | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }'
}
node_event_instructions() { # emu|reference
    local fewer more
    for _ in 1 2 3; do
        fewer=$(node_run_instructions "$1" 20000)
        more=$(node_run_instructions "$1" 60000)
        divide "$((more - fewer))" 40000 "%.0f\n"
    done | median_of
}
echo "bench: node (callgrind)" >&2
ours_node_instructions=$(node_event_instructions emu)
ref_node_instructions=$(node_event_instructions reference)
echo "bench: simulator" >&2
read -r sim_one _ _ < <("$bin/bench-node" simulator 1 $simulator_seconds)
read -r sim_many sim_many_cpu sim_many_wall < <("$bin/bench-node" simulator \
    $simulator_robots_many $simulator_seconds)
robots_per_core=$(awk -v c="$sim_many" 'BEGIN { printf "%.0f", 1 / c }')

# --- simulated arena ---------------------------------------------------------
# The dsPIC30F simulator on a compiled workload: simulated instructions per
# second of one core's CPU time (bench/dspic30_sim_bench.cpp).
echo "bench: dsPIC30F simulator" >&2
dspic30_sim_mips=$("$bin/bench-dspic30-sim" 1000000000 | awk '{ print $2 }')

# `aseba flash` of the application into one simulated e-puck (dspic30-sim,
# UART1 on a TCP port, the firmware's 115,200 baud, paced to the wall clock)
# that holds only the bootloader, so that every page is erased and written.
# The robot's seconds come from the cycles at which the console's
# connection came and went (the simulator's log); both include the
# console's first second of waiting for the robot to answer as a node.
echo "bench: aseba flash into dspic30-sim" >&2
"$bin/dspic30-sim" --uart1 tcp:0 --memory "$scratch/flash.memory" \
    "$build/dspic30/epuck-aseba-bootloader.hex" >"$scratch/flash.out" 2>"$scratch/flash.err" &
flash_simulator=$!
for _ in $(seq 100); do grep -q 'tcp:localhost;' "$scratch/flash.out" && break; sleep 0.1; done
flash_port=$(sed -n 's/.*tcp:localhost;//p' "$scratch/flash.out")
sleep 1 # the bootloader's second: no application to start, it waits
flash_start=$(date +%s.%N)
"$bin/aseba" -t "tcp:localhost;$flash_port" flash --node 1 "$build/dspic30/epuck-aseba.hex" >&2
flash_end=$(date +%s.%N)
kill -TERM "$flash_simulator"
wait "$flash_simulator"
flash_wall=$(awk -v a="$flash_start" -v b="$flash_end" 'BEGIN { printf "%.1f", b - a }')
flash_robot=$(awk '/client connected at cycle/ { from = $6 } /client gone at cycle/ { to = $6 }
    END { printf "%.1f", (to - from) / 14745600 }' "$scratch/flash.err")

echo "bench: arena" >&2
arena_goal_factor=30    # at 100 robots, every run, on an idle machine (issue 29; 10 before)
arena_goal_factor_many=2 # at 1000 robots (issue 29; 0.5 before)
arena_runs=3
arena_port=$((40000 + RANDOM % 20000))
# One run: "factor processor_factor threads": simulated seconds over
# wall-clock seconds (setup excluded) and over processor seconds (every
# thread's, setup excluded), from the line epuck-emu prints on stopping.
arena_run() { # robots simulated_seconds
    "$bin/epuck-emu" --arena default --robots "$1" --load examples/paper-annex.aesl \
        --speed max --duration "$2" --port "$arena_port" --quiet |
        sed -n 's/.*stopped at \([0-9.]*\) simulated s.*(\([0-9.]*\)x real time).*, \([0-9.]*\) s of processor time on \([0-9]*\) thread.*/\2 \1 \3 \4/p' |
        awk '{ printf "%s %.1f %s\n", $1, $2 / $3, $4 }'
}
# Several runs: "lowest highest lowest_processor highest_processor threads".
arena_factors() { # robots simulated_seconds
    local runs
    runs=$(for _ in $(seq $arena_runs); do arena_run "$1" "$2"; done)
    local wall processor
    wall=$(cut -d' ' -f1 <<<"$runs" | sort -n | sed -n '1p;$p' | tr '\n' ' ')
    processor=$(cut -d' ' -f2 <<<"$runs" | sort -n | sed -n '1p;$p' | tr '\n' ' ')
    echo "$wall $processor $(head -n 1 <<<"$runs" | cut -d' ' -f3)"
}
arena_6=$(arena_run 6 60 | cut -d' ' -f1)
read -r arena_100_low arena_100_high arena_100_cpu_low arena_100_cpu_high arena_100_threads \
    < <(arena_factors 100 10)
read -r arena_1000_low arena_1000_high arena_1000_cpu_low arena_1000_cpu_high arena_1000_threads \
    < <(arena_factors 1000 2)

# --- the STM32F4 image (ports/stm32f4, on QEMU's netduinoplus2) ----------------
echo "bench: STM32F4 image" >&2
make --no-print-directory BUILD="$build" stm32f4 "$bin/bench-qemu" >&2
stm32f4_image=$build/stm32f4/epuck-aseba-stm32f4.elf
# Code (vectors and .text), constant data, RAM (.data, .bss and the RAM kept
# across resets); .data is also in flash, but there is none.
read -r stm32f4_code stm32f4_constant stm32f4_ram < <(arm-none-eabi-size -A "$stm32f4_image" | awk '
    $1 == ".isr_vector" || $1 == ".text" { code += $2 }
    $1 == ".rodata" { constant += $2 }
    $1 == ".data" || $1 == ".bss" || $1 == ".noinit" { ram += $2 }
    END { print code, constant, ram }')
stm32f4_runs=20
stm32f4_per_step=$("$bin/bench-qemu" $stm32f4_runs 2>/dev/null | sed -n 's/^instructions per step //p')

# --- the VM on the dsPIC30F (the harness image of pic30-elf-gcc -Os, simulated) --
# bench/vm_workload.aseba on the chip's machine code, timed by its Timer2/3
# on tools/dspic30_sim (tests/ports/dspic30/dspic30_vm_bench.cpp).
echo "bench: VM on the dsPIC30F (simulated)" >&2
make --no-print-directory BUILD="$build" "$bin/bench-dspic30-vm" >&2
dspic30_vm=$("$bin/bench-dspic30-vm" 5 2>/dev/null)
dspic30_per_step=$(sed -n 's/^cycles per step //p' <<<"$dspic30_vm")
dspic30_steps_per_second=$(sed -n 's/^steps per second at 14.7456 MIPS //p' <<<"$dspic30_vm")
dspic30_annex_steps=$(sed -n 's/^paper annex steps //p' <<<"$dspic30_vm")
dspic30_annex_per_step=$(sed -n 's/^paper annex cycles per step //p' <<<"$dspic30_vm")
[ -n "$dspic30_per_step" ] || { echo "bench: bench-dspic30-vm printed no figure: $dspic30_vm" >&2; exit 1; }

# --- tools and network (edit to running, connections, flood) -----------------
echo "bench: tools and network" >&2
make --no-print-directory BUILD="$build" "$bin/bench-network" "$bin/aseba" >&2
load_runs=20
connection_cycles=1000
flood_seconds=8
read -r load_median load_min load_max < <("$bin/bench-network" load $load_runs)
connections_seconds=$("$bin/bench-network" connections $connection_cycles)
read -r rss_before rss_during rss_peak flood_mb idle_median idle_max flood_median flood_max \
    < <("$bin/bench-network" flood $flood_seconds)
network_table=$(
    echo "| figure | ours | before | goal |"
    echo "|---|---|---|---|"
    echo "| edit → running on 6 robots: \`aseba load\` of the paper annex against \`epuck-emu --robots 6\`, loopback, median of $load_runs ms (lowest–highest) | $load_median ($load_min–$load_max) | 157–177 | < 100 |"
    echo "| $connection_cycles connect/close cycles on epuck-emu's port, s | $connections_seconds | 55 | < 1 |"
    echo "| epuck-emu (6 robots) resident memory under a $flood_seconds s event flood from one client: before, during, peak, MB | $((rss_before / 1024)), $((rss_during / 1024)), $((rss_peak / 1024)) | 1,600 (never released) | bounded |"
    echo "| another client's GET_VARIABLES round trip meanwhile, median (longest) ms; without the flood | $flood_median ($flood_max); $idle_median ($idle_max) | unanswered for 28 s | the usual latency |"
    echo "| flood the network took from that client, MB in $flood_seconds s | $flood_mb | - | slowed |"
)

# --- the IDE in a browser (keystroke to compile result, Load all) ------------
# tests/ide/bench.mjs drives Debian's Chromium on the page of aseba-ide, on six
# e-pucks of the default arena running the paper's controller.
echo "bench: the IDE (headless Chromium)" >&2
make --no-print-directory BUILD="$build" "$bin/aseba-ide" tools/ide/web/node_modules/.package-lock.json >&2
ide_lines=$(BIN="$bin" node tests/ide/bench.mjs)
ide_keystroke=$(sed -n 's/^IDE keystroke to compile result[^:]*: \([0-9.]*\) ms median of \([0-9]*\) (min \([0-9.]*\), max \([0-9.]*\).*/\1 (\3–\4), median of \2/p' <<<"$ide_lines")
ide_load=$(sed -n 's/^IDE Load all to six robots running: \([0-9]*\) ms median of \([0-9]*\) (min \([0-9]*\), max \([0-9]*\)).*/\1 (\3–\4), median of \2/p' <<<"$ide_lines")
[ -n "$ide_keystroke" ] && [ -n "$ide_load" ] || { echo "bench: tests/ide/bench.mjs printed no figures: $ide_lines" >&2; exit 1; }
ide_table=$(
    echo "| figure | ours | goal |"
    echo "|---|---|---|"
    echo "| IDE: a key typed in the paper's controller to its compile result on the page, ms (lowest–highest) | $ide_keystroke | < 100 |"
    echo "| IDE: Load all to the six robots running the new program, as the page shows it, ms (lowest–highest) | $ide_load | |"
)

# --- the MQTT bridge (aseba-mqtt, mosquitto) ---------------------------------
echo "bench: MQTT bridge" >&2
make --no-print-directory BUILD="$build" "$bin/bench-mqtt" "$bin/aseba-mqtt" >&2
mqtt_seconds=10
mqtt_events=20000
mqtt_goal_median_ms=1 # robot to robot across two networks (issue 29)
mqtt_goal_p99_ms=5
read -r mqtt_median mqtt_p99 mqtt_samples < <("$bin/bench-mqtt" latency $mqtt_seconds)
read -r mqtt_out mqtt_in _ _ < <("$bin/bench-mqtt" throughput $mqtt_events)
mqtt_table=$(
    echo "| figure | ours | goal |"
    echo "|---|---|---|"
    echo "| event latency, robot → bridge → mosquitto → bridge → robot of another network, loopback: median (99th percentile) ms, $mqtt_samples events | $mqtt_median ($mqtt_p99) | ≤ $mqtt_goal_median_ms (≤ $mqtt_goal_p99_ms) |"
    echo "| events per second one bridge carries, network → broker (QoS 1), $mqtt_events events | $mqtt_out | - |"
    echo "| events per second one bridge carries, broker → network, $mqtt_events events | $mqtt_in | - |"
)

# --- the table -------------------------------------------------------------
table=$(
    echo "| figure | ours | reference | ours / reference | goal |"
    echo "|---|---|---|---|---|"
    echo "| VM: host instructions per bytecode step, as shipped (computed goto; callgrind) | $per_step_shipped | $per_step_reference | $(ratio "$per_step_shipped" "$per_step_reference") | ≤ $vm_goal_instructions |"
    echo "| VM: host instructions per bytecode step, switch dispatch (the dsPIC's; callgrind) | $per_step_switch | $per_step_reference | $(ratio "$per_step_switch" "$per_step_reference") | |"
    echo "| VM: ns per bytecode step, as shipped (best of $vm_timing_runs) | $ns_shipped | $ns_reference | $(ratio "$ns_shipped" "$ns_reference") | |"
    echo "| VM: ns per bytecode step, switch dispatch (best of $vm_timing_runs) | $ns_switch | $ns_reference | $(ratio "$ns_switch" "$ns_reference") | |"
    echo "| VM on an AVR (simavr, avr-gcc -Os): instructions (cycles) per bytecode step, switch dispatch | $avr_instructions_switch ($avr_cycles_switch) | - | - | |"
    echo "| VM on an AVR (simavr, avr-gcc -Os): instructions (cycles) per bytecode step, computed goto | $avr_instructions_goto ($avr_cycles_goto) | - | - | |"
    echo "| VM + standard natives + node protocol linked, avr-gcc -Os (16-bit int): code + const data, bytes | $avr_flash (code $avr_code) | paper budget $paper_budget_bytes | $(ratio "$avr_flash" "$paper_budget_bytes") of budget | ≤ $paper_budget_bytes, aim $avr_aim_bytes |"
    echo "| VM + standard natives + node protocol linked, Cortex-M4 -Os: code + const data, bytes | $arm_flash (code $arm_code) | paper budget $paper_budget_bytes | $(ratio "$arm_flash" "$paper_budget_bytes") of budget | ≤ $paper_budget_bytes |"
    echo "| RAM of the e-puck firmware, linked 16-bit image (avr-gcc), bytes: VM memory $ram_vm_memory, node $ram_node (receive frame $ram_frame), main loop $ram_loop, drivers $ram_devices, board $ram_board, other $ram_other | $ram_total | paper $ram_goal_bytes | $(ratio "$ram_total" "$ram_goal_bytes") of the paper's | ≤ $ram_goal_bytes |"
    echo "| compiler: paper annex (paper's dialect, e-puck), ms, mean of $((compiler_runs * 10)) | $(compiler_field paper-annex 2) | cannot compile it | - | |"
    echo "| compiler: paper annex in today's dialect (e-puck), ms, mean of $((compiler_runs * 10)) | $(compiler_field paper-annex-today 2) | $(compiler_field paper-annex-today 3) | $(ratio "$(compiler_field paper-annex-today 2)" "$(compiler_field paper-annex-today 3)") | ≤ ${compiler_goal_ratio}× |"
    echo "| compiler: generated 1,000-line script ($(compiler_field generated-1000 4) words), ms, mean of $compiler_runs | $(compiler_field generated-1000 2) | $(compiler_field generated-1000 3) | $(ratio "$(compiler_field generated-1000 2)" "$(compiler_field generated-1000 3)") | ≤ ${compiler_goal_ratio}× |"
    echo "| compiler: the whole process, start-up included: \`asebac examples/paper-annex.aesl -o /dev/null\`; the reference behind the least of a command (bench-reference-compile) on the same controller in today's dialect, ms, median of $compiler_process_runs | $process_ours | $process_reference | $(ratio "$process_ours" "$process_reference") | ≤ ${compiler_goal_ratio}× |"
    echo "| node: GET_VARIABLES → VARIABLES round trip, loopback TCP, median µs (mean) | $ours_latency_median ($ours_latency_mean) | $ref_latency_median ($ref_latency_mean) | $(ratio "$ours_latency_median" "$ref_latency_median") | |"
    echo "| node: user events per second (ping → pong, 16 in flight), median of $node_runs runs of $node_run_events (range) | $ours_events ($ours_events_range) | $ref_events ($ref_events_range) | $(ratio "$ours_events" "$ref_events") | ≥ ${node_goal_ratio}× |"
    echo "| node: user events per second of a node that answers at once (\`bench-node at-once\`: about the most this client measures), median of $node_runs runs (range) | $at_once_events ($at_once_events_range) | - | - | |"
    echo "| node: host instructions per user event (ping → pong), the whole process, start-up excluded (callgrind) | $ours_node_instructions | $ref_node_instructions | $(ratio "$ours_node_instructions" "$ref_node_instructions") | < 1× |"
    echo "| DSP: host instructions for one 64-point dsp.fft (callgrind) | $fft_instructions | - | - | |"
    echo "| DSP: host instructions for one dsp.fir, 64 samples through 32 taps (callgrind) | $fir_instructions | - | - | |"
    echo "| DSP natives: code, avr-gcc -Os (16-bit int), bytes, objects alone | $dsp_avr_code | - | - | |"
    echo "| simulator: CPU s per robot-second, 1 robot running the paper annex | $sim_one | - | - | |"
    echo "| simulator: CPU s per robot-second, $simulator_robots_many robots ($sim_many_cpu s CPU in $sim_many_wall s) | $sim_many | - | - | |"
    echo "| simulator: robots one core would keep in real time (extrapolated from the line above; epuck-emu runs at most 1000) | ≈ $robots_per_core | - | - | |"
    echo "| arena: real-time factor, default arena, 6 robots running the paper annex (60 simulated s) | ${arena_6}× | - | - | |"
    echo "| arena: real-time factor, default arena, 100 robots running the paper annex (10 simulated s, $arena_100_threads threads), lowest–highest of $arena_runs runs; simulated s per processor s | ${arena_100_low}–${arena_100_high}×; ${arena_100_cpu_low}–${arena_100_cpu_high}× | - | - | ≥ ${arena_goal_factor}×, every run |"
    echo "| arena: real-time factor, default arena, 1000 robots running the paper annex (2 simulated s, $arena_1000_threads threads), lowest–highest of $arena_runs runs; simulated s per processor s | ${arena_1000_low}–${arena_1000_high}×; ${arena_1000_cpu_low}–${arena_1000_cpu_high}× | - | - | ≥ ${arena_goal_factor_many}× |"
    echo "| STM32F4 image (make stm32f4, QEMU board, -O2): code / constant data / RAM, bytes | $stm32f4_code / $stm32f4_constant / $stm32f4_ram | - | - | |"
    echo "| VM on the Cortex-M4 (QEMU -icount): instructions per bytecode step, computed goto | $stm32f4_per_step | - | - | |"
    echo "| dsPIC30F simulator (tools/dspic30_sim): million simulated instructions per second of one core, bench/dspic30_workload.c | $dspic30_sim_mips | - | - | ≥ 100 |"
    echo "| dsPIC30F simulator: \`aseba flash\` of the application into one robot holding only its bootloader, UART1 on TCP at 115,200 baud, paced: seconds of the robot's clock / of the wall clock | $flash_robot / $flash_wall | - | - | |"
)

dspic_table=$(
    echo "| figure (make dspic30, pic30-elf-gcc -Os, linked) | dsPIC30F6014A | avr-gcc | Cortex-M4 | goal |"
    echo "|---|---|---|---|---|"
    echo "| VM + standard natives + node: code + constants, bytes (3 per instruction word on the dsPIC) | $dspic_core_bytes ($dspic_core_code + $dspic_core_const words) | $avr_flash | $arm_flash | ≤ $paper_budget_bytes (paper) |"
    echo "| application image: code + constants, instruction words (bytes) | $(dspic_of application_code) + $(dspic_of application_const) ($(bytes_of_words $(($(dspic_of application_code) + $(dspic_of application_const))))) | - | - | below the descriptor, 45,216 words |"
    echo "| application by part, code + constants, words | $dspic_parts | - | - | |"
    echo "| bootloader image: code + constants, instruction words (bytes) | $(dspic_of bootloader_code) + $(dspic_of bootloader_const) ($(bytes_of_words $(($(dspic_of bootloader_code) + $(dspic_of bootloader_const))))) | - | - | ≤ 2,048 words (64 rows) |"
    echo "| VM: cycles per bytecode step, switch dispatch, bench/vm_workload.aseba (dsPIC: simulated, Timer2/3; AVR: simavr; Cortex-M4: QEMU instructions, computed goto) | $dspic30_per_step | $avr_cycles_switch | $stm32f4_per_step | |"
    echo "| VM: bytecode steps per second at the e-puck's 14.7456 MIPS | $dspic30_steps_per_second | - | - | |"
    echo "| VM: the paper's controller (examples/paper-annex.aesl), its ir_sensors event with every sensor at 0: steps, cycles per step (natives included) | $dspic30_annex_steps, $dspic30_annex_per_step | - | - | |"
    echo "| RAM of the application, bytes: VM memory $dspic_ram_vm, node $dspic_ram_node (receive frame $(dspic_of node_receive_frame)), main loop $dspic_ram_loop, drivers $(dspic_of robot_devices), board $(dspic_of board), other $dspic_ram_other; the stack gets the rest | $dspic_ram_total (+ $(dspic_of ram_stack) stack) | $ram_total | $stm32f4_ram | ≤ $ram_goal_bytes (paper) |"
)

# What follows this line in the report is written by hand and kept.
notes_marker='<!-- Written by hand below this line: make bench keeps it. -->'
notes=""
if [ -f "$report" ] && grep -qF "$notes_marker" "$report"; then
    notes=$(awk -v marker="$notes_marker" '$0 == marker { found = 1 } found' "$report")
fi

cpu_model=$(awk -F': ' '/^model name/ { print $2; exit }' /proc/cpuinfo)
cores=$(nproc)
{
    echo "# Benchmarks"
    echo
    echo "Measured by \`make bench\` (scripts/bench.sh, programs in bench/) on"
    echo "$cpu_model, $cores cores, $(date -u '+%Y-%m-%d %H:%M UTC'). This file is"
    echo "replaced on every run but for its last part, written by hand. The reference"
    echo "is Debian's \`aseba\` 1.6.99, measured in the same run. Load average (1 min)"
    echo "$load_at_start at the start, $(cut -d' ' -f1 /proc/loadavg) at the end: the timed figures are"
    echo "only comparable between runs of a similar load; sizes, instruction and cycle"
    echo "counts do not depend on it."
    echo
    echo "$table"
    echo
    echo "## The e-puck's dsPIC30 images"
    echo
    echo "From the programs \`make dspic30\` links (the GPL pic30-elf-gcc 4.5.1 of XC16"
    echo "v2.10, -Os): bench/dspic30_sizes.py reads the linker's map files, input"
    echo "section by input section, and sizes the RAM's parts with the dsPIC compiler"
    echo "(bench/ram_parts.c). The avr-gcc and Cortex-M4 columns are the proxies of the"
    echo "table above, for comparison."
    echo
    echo "$dspic_table"
    echo
    echo "## The group IDE"
    echo
    echo "$ide_table"
    echo
    echo "Measured by \`tests/ide/bench.mjs\` in headless Chromium on the page of"
    echo "\`aseba-ide\`, against \`epuck-emu --arena default\` (six robots) with the"
    echo "paper's controller: the time from the keydown to the page painting the"
    echo "compile result of the new text, one key every 150 ms; and from the click"
    echo "on Load all to every robot shown running the new program."
    echo
    echo "## Tools and network"
    echo
    echo "$network_table"
    echo
    echo "Measured by \`bench-network\` (bench/network_bench.cpp) against an"
    echo "\`epuck-emu\` it starts on a free loopback port: \`bench-network load"
    echo "$load_runs\` times \`aseba -t TARGET load examples/paper-annex.aesl\` (the"
    echo "whole program: start, connect, discover and describe the six robots,"
    echo "compile, upload, run); \`bench-network connections $connection_cycles\` connects"
    echo "and closes one socket after the other, then checks the emulator still"
    echo "answers; \`bench-network flood $flood_seconds\` sends user events from one client"
    echo "as fast as the network reads them while another client reads a variable"
    echo "of robot 1 every 50 ms, and reads VmRSS and VmHWM of /proc/PID/status."
    echo "The \"before\" column quotes the measurements of the issues that asked"
    echo "for these figures."
    echo
    echo "## MQTT bridge"
    echo
    echo "$mqtt_table"
    echo
    echo "Measured by \`bench-mqtt\` (bench/mqtt_bench.cpp) with Debian's mosquitto"
    echo "on a free loopback port. Latency: \`bench-mqtt latency $mqtt_seconds\`, two"
    echo "\`epuck-emu\` (real time), each behind its \`aseba-mqtt --accept-events\`; the"
    echo "robot of the first emits tick(n) every 20 ms (bench/mqtt_ticker.aesl), the"
    echo "robot of the second answers tock(n) (bench/mqtt_echo.aesl); the time from"
    echo "tick(n) heard on the first network to tock(n) heard on the second. Events"
    echo "per second: \`bench-mqtt throughput $mqtt_events\`, one bridge in front of a"
    echo "network of the benchmark's own that writes robot events as fast as the"
    echo "bridge reads them (so that no simulated robot sets the pace), until a"
    echo "subscriber has them all; then as many events published on the broker, until"
    echo "the network has them all."
    echo
    echo "## How each figure is measured"
    echo
    echo "- VM: \`bench/vm_workload.aseba\` (nested loops with arithmetic and array"
    echo "  reads and writes) is compiled once by our compiler for the dummy node; the"
    echo "  same bytecode runs on our VM (\`bench-vm\`: as the host tools build it,"
    echo "  computed goto; \`bench-vm-switch\`: the switch dispatch of the dsPIC build)"
    echo "  and on Debian's libasebavm.a. Steps: $steps, counted one vm_step at a time"
    echo "  on our VM and one AsebaVMRun(1) at a time on the reference (\`bench-vm steps"
    echo "  ours\` checks both counts and the final variables agree). Instructions:"
    echo "  \`valgrind --tool=callgrind --toggle-collect=vm_run --toggle-collect='vm_run.*'\`"
    echo "  (the link-time optimiser's copies of vm_run; \`AsebaVMRun\` for the"
    echo "  reference) around \`bench-vm once ours\`, divided by the steps. Time:"
    echo "  \`bench-vm time ours $vm_timing_runs\`, the best run, divided by the steps."
    echo "- VM on an AVR: \`bench-vm header\` writes the same bytecode into a header that"
    echo "  bench/avr_workload.c includes; built for an ATmega1284P with avr-gcc -Os"
    echo "  (vm/*.c, the switch or computed goto), \`avr-step-counter\` runs it under"
    echo "  simavr one instruction at a time and counts the instructions and cycles of"
    echo "  event \`go\`, divided by the steps; the variables' checksum must be the"
    echo "  host's (\`bench-vm checksum ours\`: $host_checksum)."
    echo "- Code size: \`scripts/cross-check.sh\` on vm/*.c and the standard natives"
    echo "  (nat_arguments, nat_math, nat_trigonometry, nat_deque, nat_standard); the"
    echo "  table quotes its linked image (tests/cross/node_image.c, unused functions"
    echo "  dropped, the compiler's support library included). Its whole output:"
    echo
    echo '```'
    echo "$sizes"
    echo '```'
    echo
    echo "- RAM: \`bench/firmware_ram.sh\` links the dsPIC application's sources"
    echo "  (\`make -s sources-DSPIC30_APPLICATION\`, the portable DSP kernel for the"
    echo "  DSP-engine one) with avr-gcc -Os, 16-bit int, against one volatile word"
    echo "  for the chip's registers (bench/ram_image.c), and sums the .data and .bss"
    echo "  input sections of its map, constants excluded (XC16 keeps those in flash);"
    echo "  bench/ram_parts.c sizes the parts. The e-puck's memories are those of its"
    echo "  description: bytecode $(($(ram_of vm_bytecode) / 2)) words, stack $(($(ram_of vm_stack) / 2)), variables $(($(ram_of vm_variables) / 2))."
    echo "  The C call stack comes on top."
    echo "- Compiler: \`bench-compiler $compiler_runs\`, wall-clock mean. The reference"
    echo "  runs through tests/compiler/reference_oracle.cpp and must give the same"
    echo "  bytecode. The 1,000-line script is generated by bench/compiler_bench.cpp"
    echo "  (\`bench-compiler 1 --print-generated\` prints it)."
    echo "- Node: \`bench-node emu\` starts \`epuck-emu --robots 1\`, \`bench-node"
    echo "  reference\` starts \`asebadummynode\`, each on a free loopback port, and"
    echo "  talks to it directly (TCP_NODELAY, TCP_QUICKACK, reads that spin rather than"
    echo "  sleep): 2,000 GET_VARIABLES of 16"
    echo "  words, then $node_run_events user events through a handler \`onevent ping emit pong\`"
    echo "  loaded with SET_BYTECODE, RESET, RUN; $node_runs runs of each node, interleaved,"
    echo "  and the median of each. \`bench-node at-once\` runs the same client against"
    echo "  a node of a few lines in bench-node itself that answers each message at"
    echo "  once, spinning on its socket (no VM, no queue, no sleep): about the most"
    echo "  this client can measure. It and the client leave the two cores no room for"
    echo "  anything else, so its runs vary the most: its median can fall below ours."
    echo "  Instructions: the same with the"
    echo "  node under \`valgrind --tool=callgrind\` (BENCH_NODE_UNDER), 20,000 then"
    echo "  60,000 events (\`bench-node emu 60000\`): the difference of the whole"
    echo "  process's counts over the 40,000 more, the median of three such pairs."
    echo "- DSP: \`valgrind --tool=callgrind --toggle-collect=nat_dsp_fft_function"
    echo "  bench-dsp fft\` (and \`fir\` with nat_dsp_fir_function) counts one call on"
    echo "  fixed data; the code size sums .text of native_functions/nat_dsp*.c built"
    echo "  alone with avr-gcc -Os."
    echo "- Simulator: \`bench-node simulator N $simulator_seconds\` runs \`epuck-emu"
    echo "  --robots N --load examples/paper-annex.aesl\` for $simulator_seconds s of wall"
    echo "  time and divides the CPU time it used by N × seconds."
    echo "- Arena: \`epuck-emu --arena default --robots N --load examples/paper-annex.aesl"
    echo "  --speed max --duration S\` (one process, its default threads: one per core"
    echo "  with 64 robots or more each); the factor is the simulated time over the"
    echo "  wall-clock time of the run, setup excluded, as epuck-emu prints it when it"
    echo "  stops, $arena_runs runs for 100 and 1000 robots. The wall clock depends on what"
    echo "  else the computer runs: beside it, the simulated time over the processor"
    echo "  time of every thread (setup excluded), which does not. The square grows"
    echo "  with N (about 20 cm × 20 cm per robot, docs/arena-format.md)."
    echo "- STM32F4: \`make stm32f4\`, sizes by \`arm-none-eabi-size -A\` (code: the"
    echo "  vectors and .text; RAM: .data, .bss and the RAM the board keeps across resets"
    echo "  for its store, 16 KiB). Instructions: \`bench-qemu $stm32f4_runs\` runs the VM"
    echo "  workload above on the harness image (tests/ports/stm32f4/target) in QEMU with"
    echo "  \`-icount shift=0\` (the guest's clock counts instructions); the image counts"
    echo "  the handler's steps one vm_step at a time, then times $stm32f4_runs runs to"
    echo "  the end with SysTick, and a loop of known instructions converts its clock to"
    echo "  instructions."
    if [ -n "$notes" ]; then
        echo
        echo "$notes"
    fi
} >"$report"
echo "$table"
echo
echo "$dspic_table"
echo
echo "$network_table"
echo
echo "$ide_table"
echo
echo "$mqtt_table"
echo "bench: written to $report" >&2
