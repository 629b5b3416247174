#!/usr/bin/env bash
# Builds the portable layers (VM, natives) with avr-gcc, whose `int` is 16
# bits like the dsPIC's, and with arm-none-eabi-gcc for a Cortex-M4, warnings
# as errors, and prints their code and data sizes.
# Usage: cross-check.sh BUILD_DIR SOURCE...
set -euo pipefail
build=$1
shift

flags=(-std=gnu99 -Os -ffreestanding -Wall -Wextra -Werror -Wshadow -Wundef
       -ffunction-sections -fdata-sections -Ivm -Inative_functions -I.)

check() { # name compiler size-tool extra-flags...
    local name=$1 compiler=$2 size_tool=$3
    shift 3
    local out=$build/cross-$name
    mkdir -p "$out"
    local objects=()
    for source in "${sources[@]}"; do
        local object=$out/$(echo "${source%.c}" | tr / _).o
        "$compiler" "${flags[@]}" "$@" -c "$source" -o "$object"
        objects+=("$object")
    done
    echo "== $name ($compiler $*)"
    "$size_tool" -t "${objects[@]}"
}

sources=("$@")
check avr avr-gcc avr-size -mmcu=atmega1284p
check arm arm-none-eabi-gcc arm-none-eabi-size -mcpu=cortex-m4 -mthumb
