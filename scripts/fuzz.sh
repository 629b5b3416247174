#!/usr/bin/env bash
# Builds libFuzzer targets with clang (ASan + UBSan) and runs each for a
# bounded time. Any crash stops with a non-zero status; its input is kept in
# BUILD_DIR/fuzz/<target>/ to become a regression test.
# Usage: scripts/fuzz.sh SECONDS BUILD_DIR [TARGET...]   (default: every target)
# The random seed is FUZZ_SEED (default 1), so that a CI run can be replayed.
set -euo pipefail
seconds=$1
build=$2
shift 2

# The project's libraries, as the Makefile lists them.
library() { make -s --no-print-directory "sources-$1"; }
# shellcheck disable=SC2207 # the definitions are words
cxx_defines=($(make -s --no-print-directory print-CXX_DEFINES))
vm_sources=$(library aseba_vm)
natives_sources="$vm_sources $(library aseba_natives)"
compiler_sources="$natives_sources $(library aseba_compiler)"
client_sources="$compiler_sources $(library aseba_client)"

# TARGET: its sources (C files are the portable layers under test, compiled
# for coverage; C++ files the harness), extra link flags and input size limit.
declare -A sources=(
    [vm]="$vm_sources tests/fuzz/vm_fuzzer.cpp tests/vm/fuzz_driver.cpp
          tests/support/vm_harness.cpp"
    [node]="$natives_sources $(library aseba_node) tests/fuzz/node_fuzzer.cpp
            tests/node/node_harness.cpp tests/node/reference_decoder.cpp"
    [compiler]="$compiler_sources tests/fuzz/compiler_fuzzer.cpp"
    [client]="$client_sources tests/fuzz/client_fuzzer.cpp"
    [files]="$vm_sources $(library aseba_node) $(library aseba_flash) tools/emulator/arena_file.cpp
             tests/fuzz/files_fuzzer.cpp"
    [formats]="$compiler_sources tests/fuzz/formats_fuzzer.cpp"
    [command_line]="$client_sources tools/console/options.cpp tests/fuzz/command_line_fuzzer.cpp"
    [ide]="$client_sources tools/ide/requests.cpp tests/fuzz/ide_requests_fuzzer.cpp"
    [dspic30_sim]="$(library dspic30_sim) tests/fuzz/dspic30_sim_fuzzer.cpp"
)
# The compiler reads projects with pugixml; the client's links use asio,
# whose resolver runs a thread.
declare -A link_flags=([vm]="" [node]="-lasebacommon" [compiler]="-lpugixml"
                       [client]="-lpugixml -pthread" [files]="" [formats]="-lpugixml"
                       [command_line]="-lpugixml -pthread" [ide]="-lpugixml -pthread"
                       [dspic30_sim]="")
declare -A max_length=([vm]=1024 [node]=4096 [compiler]=1048576 [client]=4096 [files]=8192
                       [formats]=8192 [command_line]=512 [ide]=4096 [dspic30_sim]=4096)
# Folders of real inputs a target starts from, besides its own corpus.
declare -A seeds=([compiler]="examples tests/compiler/programs"
                  [files]="tests/bootloader/hex tests/arena/data"
                  [formats]="examples tests/interop/programs tests/fuzz/seeds/formats"
                  [ide]="tests/ide_server/data")

targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(vm node compiler client files formats command_line ide dspic30_sim)

# Line tables only: what a crash's report prints, for less compile time.
sanitize=(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
          -gline-tables-only -O1)
includes=(-I. -Ivm -Inative_functions -isystem /usr/include/aseba
          '-DTARGET_CONFIG="boards/epuck_host/epuck_host_config.h"')

for target in "${targets[@]}"; do
    [ -n "${sources[$target]:-}" ] || { echo "fuzz: unknown target '$target'" >&2; exit 2; }
done
jobs=$(nproc 2>/dev/null || echo 2)

# Runs FUNCTION ITEM for each item, $jobs at a time; fails if one failed.
in_parallel() { # function item...
    local run=$1 item pending=0 status=0
    shift
    for item in "$@"; do
        "$run" "$item" &
        pending=$((pending + 1))
        if [ "$pending" -ge "$jobs" ]; then
            wait -n || status=1
            pending=$((pending - 1))
        fi
    done
    while [ "$pending" -gt 0 ]; do
        wait -n || status=1
        pending=$((pending - 1))
    done
    return $status
}

# Every source once, whichever targets share it (the compiler's library
# is in five), several at a time: C files as the host build compiles them,
# with the host target's configuration (the VM with computed goto).
objects_dir=$build/fuzz/obj
mkdir -p "$objects_dir"
object_of() { echo "$objects_dir/$(echo "$1" | tr / _).o"; }
compile() { # source
    local object
    object=$(object_of "$1")
    case $1 in
    *.c) clang -std=gnu99 -Wall -Wextra -Werror "${sanitize[@]}" -fsanitize=fuzzer-no-link \
             "${includes[@]}" -c "$1" -o "$object" ;;
    *.cpp) clang++ -std=c++20 "${cxx_defines[@]}" -Wall -Wextra -Werror "${sanitize[@]}" \
             -fsanitize=fuzzer-no-link "${includes[@]}" -c "$1" -o "$object" ;;
    esac
}
# shellcheck disable=SC2207 # sources are words
all_sources=($(for target in "${targets[@]}"; do printf '%s\n' ${sources[$target]}; done | sort -u))
echo "fuzz: compiling ${#all_sources[@]} sources for ${#targets[@]} targets"
in_parallel compile "${all_sources[@]}" || { echo "fuzz: a source did not compile" >&2; exit 1; }

# Links and runs one target; its lines go to its log's summary.
fuzz_one() { # target
    local target=$1 out=$build/fuzz/$1 objects=() source
    mkdir -p "$out/corpus"
    for source in ${sources[$target]}; do objects+=("$(object_of "$source")"); done
    # shellcheck disable=SC2086 # link flags are words
    clang++ "${sanitize[@]}" -fsanitize=fuzzer "${objects[@]}" ${link_flags[$target]} \
        -o "$out/fuzzer" || return 1
    # shellcheck disable=SC2086 # seed folders are words
    if ! "$out/fuzzer" -seed="${FUZZ_SEED:-1}" -max_total_time="$seconds" \
        -max_len="${max_length[$target]}" -artifact_prefix="$out/" -print_final_stats=1 \
        "$out/corpus" ${seeds[$target]:-} 2>"$out/log"; then
        tail -n 40 "$out/log"
        echo "fuzz: $target found a crash, kept in $out/" >&2
        return 1
    fi
    echo "fuzz: $target for $seconds s: $(grep -E "stat::number_of_executed_units|Done [0-9]+ runs" \
        "$out/log" | tail -n 1)"
}

# The targets, as many at a time as there are processors (each fuzzer is
# one process): the same time per target, in a fraction of the wall clock.
echo "fuzz: ${#targets[@]} targets for $seconds s each, $jobs at a time"
in_parallel fuzz_one "${targets[@]}"
