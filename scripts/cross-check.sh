#!/usr/bin/env bash
# Builds the portable layers (VM, node protocol, natives, firmware, drivers,
# store and bootloader core) with avr-gcc, whose `int` is 16 bits like the
# dsPIC's, and with arm-none-eabi-gcc for a Cortex-M4, warnings as errors,
# against the e-puck target's configuration (hal/dspic30/dspic30_config.h),
# and prints their code and constant-data sizes per layer.
# Usage: cross-check.sh BUILD_DIR SOURCE...
set -euo pipefail
build=$1
shift
sources=("$@")

flags=(-std=gnu99 -Os -ffreestanding -Wall -Wextra -Werror -Wshadow -Wundef
       -ffunction-sections -fdata-sections -Ivm -Inative_functions -I.
       '-DTARGET_CONFIG="hal/dspic30/dspic30_config.h"')

# The layer a source belongs to, for the size table.
layer_of() {
    case $1 in
    vm/node*) echo "node protocol" ;;
    vm/*) echo "vm" ;;
    native_functions/nat_dsp*) echo "dsp natives" ;;
    drivers/*) echo "drivers" ;;
    firmware/*) echo "firmware" ;;
    bootloader/*) echo "storage, bootloader" ;;
    native_functions/*) echo "natives" ;;
    *) echo "other" ;;
    esac
}

check() { # name compiler size-tool flags...
    local name=$1 compiler=$2 size_tool=$3
    shift 3
    local out=$build/cross-$name
    mkdir -p "$out"
    echo "== $compiler $* -Os"
    for source in "${sources[@]}"; do
        local object
        object=$out/$(echo "${source%.c}" | tr / _).o
        "$compiler" "${flags[@]}" "$@" -c "$source" -o "$object"
        # Code is .text; constant data (.rodata, tables in program memory)
        # also ends up in flash.
        "$size_tool" -A "$object" | awk -v layer="$(layer_of "$source")" '
            $1 ~ /^\.text/ { code += $2 }
            $1 ~ /^\.(rodata|progmem)/ { constant += $2 }
            $1 ~ /^\.(data|bss)/ { ram += $2 }
            END { printf "%s\t%d\t%d\t%d\n", layer, code, constant, ram }'
    done | awk -F'\t' '
        { code[$1] += $2; constant[$1] += $3; ram[$1] += $4; order[$1] = 1 }
        END {
            printf "  %-16s %8s %12s %6s\n", "layer", "code", "const data", "RAM"
            for (layer in order) {
                printf "  %-16s %8d %12d %6d\n", layer, code[layer], constant[layer], ram[layer]
                total_code += code[layer]; total_constant += constant[layer]; total_ram += ram[layer]
            }
            printf "  %-16s %8d %12d %6d   bytes\n", "total", total_code, total_constant, total_ram
        }'
}

# What the layers cost in a real image: the VM, the natives and the node
# linked into the smallest firmware-like program, unused functions dropped,
# the compiler's support library (32-bit arithmetic) included.
image() { # name compiler size-tool flags...
    local name=$1 compiler=$2 size_tool=$3
    shift 3
    local elf=$build/cross-$name/node-image.elf
    local layers=()
    for source in "${sources[@]}"; do
        case $source in vm/* | native_functions/*) layers+=("$source") ;; esac
    done
    "$compiler" "${flags[@]}" "$@" -Wl,--gc-sections "${layers[@]}" tests/cross/node_image.c \
        -o "$elf"
    "$size_tool" -A "$elf" | awk -v name="$name" '
        $1 ~ /^\.(text|init|fini)/ { code += $2 }
        $1 ~ /^\.rodata/ { constant += $2 }
        $1 ~ /^\.data$/ { data += $2 }
        END { printf "  linked image (vm + natives + node): %d bytes of code, %d of constant data%s\n",
                     code, constant + (name == "avr" ? data : 0),
                     name == "avr" ? " (avr copies it to RAM)" : "" }'
}

# A proxy of the Aseba bootloader image's size (linker/epuck-bootloader.gld
# gives it 2048 instructions): its program, the bootloader core, the store
# (for the settings), the HAL's clock, pins, UART and flash against
# simulated registers (tests/cross/bootloader_image.c), linked with unused
# functions dropped. bootloader/README.md turns these bytes into dsPIC
# instructions.
bootloader_image() { # name compiler size-tool flags...
    local name=$1 compiler=$2 size_tool=$3
    shift 3
    local elf=$build/cross-$name/bootloader-image.elf
    "$compiler" "${flags[@]}" "$@" -DDSPIC30_SIMULATED_REGISTERS -Wl,--gc-sections \
        hal/dspic30/dspic30_bootloader_main.c bootloader/bootloader.c \
        bootloader/boot_application.c bootloader/bytecode_store.c \
        hal/dspic30/dspic30_clock.c hal/dspic30/dspic30_gpio.c hal/dspic30/dspic30_uart.c \
        hal/dspic30/dspic30_nvm.c drivers/epuck/epuck_selector.c vm/node_description.c \
        tests/cross/bootloader_image.c -o "$elf"
    "$size_tool" -A "$elf" | awk '
        $1 ~ /^\.(text|init|fini|vectors)/ { code += $2 }
        $1 ~ /^\.rodata/ { constant += $2 }
        $1 ~ /^\.data$/ { data += $2 }
        $1 ~ /^\.bss$/ { bss += $2 }
        END { printf "  linked bootloader image: %d bytes of code, %d of constant data, %d of initialised data, %d of RAM\n",
                     code, constant, data, data + bss }'
}

check avr avr-gcc avr-size -mmcu=atmega1284p
image avr avr-gcc avr-size -mmcu=atmega1284p
bootloader_image avr avr-gcc avr-size -mmcu=atmega1284p
check arm arm-none-eabi-gcc arm-none-eabi-size -mcpu=cortex-m4 -mthumb
image arm arm-none-eabi-gcc arm-none-eabi-size -mcpu=cortex-m4 -mthumb --specs=nano.specs \
    --specs=nosys.specs
bootloader_image arm arm-none-eabi-gcc arm-none-eabi-size -mcpu=cortex-m4 -mthumb \
    --specs=nano.specs --specs=nosys.specs
