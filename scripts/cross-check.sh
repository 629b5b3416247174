#!/usr/bin/env bash
# Builds the portable layers (VM, node protocol, natives, store, bootloader
# core, firmware, the robot's package and devices) with avr-gcc, whose `int`
# is 16 bits like the dsPIC's, and with arm-none-eabi-gcc for a Cortex-M4,
# warnings as errors, against the e-puck target's configuration
# (boards/epuck_dspic30/epuck_dspic30_config.h), and prints their code and
# constant-data sizes per layer.
# Usage: cross-check.sh BUILD_DIR SOURCE...
set -euo pipefail
build=$1
shift
sources=("$@")

flags=(-std=gnu99 -Os -ffreestanding -Wall -Wextra -Werror -Wshadow -Wundef
       -ffunction-sections -fdata-sections -Ivm -Inative_functions -I.
       '-DTARGET_CONFIG="boards/epuck_dspic30/epuck_dspic30_config.h"')

# The layer a source belongs to, for the size table.
layer_of() {
    case $1 in
    vm/node*) echo "node protocol" ;;
    vm/*) echo "vm" ;;
    native_functions/nat_dsp*) echo "dsp natives" ;;
    robots/*/devices/*) echo "robot devices" ;;
    robots/*) echo "robot package" ;;
    firmware/*) echo "firmware" ;;
    store/* | bootloader/*) echo "storage, bootloader" ;;
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
# the compiler's support library (32-bit arithmetic) included. The C
# library's start-up files are left out (main is the entry): they are the
# probe program's, not the layers' (newlib's crt0 and exit handlers took 990
# bytes on the Cortex-M4, avr's vector table and start-up 168).
image() { # name compiler size-tool flags...
    local name=$1 compiler=$2 size_tool=$3
    shift 3
    local elf=$build/cross-$name/node-image.elf
    local layers=()
    for source in "${sources[@]}"; do
        case $source in vm/* | native_functions/*) layers+=("$source") ;; esac
    done
    "$compiler" "${flags[@]}" "$@" -nostartfiles -Wl,-e,main -Wl,--gc-sections "${layers[@]}" \
        tests/cross/node_image.c -o "$elf"
    "$size_tool" -A "$elf" | awk -v name="$name" '
        $1 ~ /^\.(text|init|fini)/ { code += $2 }
        $1 ~ /^\.rodata/ { constant += $2 }
        $1 ~ /^\.data$/ { data += $2 }
        END { printf "  linked image (vm + natives + node): %d bytes of code, %d of constant data%s\n",
                     code, constant + (name == "avr" ? data : 0),
                     name == "avr" ? " (avr copies it to RAM)" : "" }'
}

# Proxies of the two dsPIC images' sizes: each image's sources as `make
# dspic30` links them (ports/dspic30/module.mk), against simulated registers
# (tests/cross/simulated_registers.c, with the portable DSP kernel for the
# DSP engine's, without the reset code in dsPIC assembly, a loop for the
# camera's timed row read: tests/cross/application_image.c), unused functions
# dropped. linker/epuck-bootloader.gld gives
# the bootloader 2048 instructions (bootloader/README.md turns its bytes
# into instructions); the application's RAM must fit the chip's 8 KB.
dspic30_image() { # image(application|bootloader) name compiler size-tool flags...
    local image=$1 name=$2 compiler=$3 size_tool=$4
    shift 4
    local elf=$build/cross-$name/$image-image.elf
    local upper=${image^^}
    local image_sources
    # shellcheck disable=SC2207 # the list is words
    image_sources=($(env -u MAKEFLAGS -u MFLAGS make -s --no-print-directory "sources-DSPIC30_$upper" |
                         tr ' ' '\n' | grep -v '\.s$' | grep -v 'boards/epuck_dspic30/dspic30_camera_row.c' |
                         sed 's|ports/dspic30/dspic30_dsp_kernel.c|native_functions/nat_dsp_kernel.c|'))
    "$compiler" "${flags[@]}" "$@" -DDSPIC30_SIMULATED_REGISTERS -Wl,--gc-sections \
        "${image_sources[@]}" tests/cross/simulated_registers.c "tests/cross/${image}_image.c" \
        -o "$elf"
    # The simulated register file is no RAM of the chip's.
    local simulated
    simulated=$("${size_tool%size}nm" -S "$elf" | awk '$4 == "registers" { print $2 }')
    simulated=$((16#${simulated:-0}))
    "$size_tool" -A "$elf" | awk -v image="$image" -v simulated="$simulated" '
        $1 ~ /^\.(text|init|fini|vectors)/ { code += $2 }
        $1 ~ /^\.rodata/ { constant += $2 }
        $1 ~ /^\.data$/ { data += $2 }
        $1 ~ /^\.bss$/ { bss += $2 }
        END { printf "  linked %s image: %d bytes of code, %d of constant data, %d of initialised data, %d of RAM\n",
                     image, code, constant, data, data + bss - simulated }'
}

check avr avr-gcc avr-size -mmcu=atmega1284p
image avr avr-gcc avr-size -mmcu=atmega1284p
dspic30_image bootloader avr avr-gcc avr-size -mmcu=atmega1284p
dspic30_image application avr avr-gcc avr-size -mmcu=atmega1284p
check arm arm-none-eabi-gcc arm-none-eabi-size -mcpu=cortex-m4 -mthumb
image arm arm-none-eabi-gcc arm-none-eabi-size -mcpu=cortex-m4 -mthumb --specs=nano.specs \
    --specs=nosys.specs
dspic30_image bootloader arm arm-none-eabi-gcc arm-none-eabi-size -mcpu=cortex-m4 -mthumb \
    --specs=nano.specs --specs=nosys.specs
