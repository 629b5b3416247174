#!/usr/bin/env bash
# The RAM of the e-puck firmware, measured on a linked 16-bit image: the
# dsPIC application's sources (as ports/dspic30/module.mk lists them, the
# portable DSP kernel standing for the DSP-engine one, without the reset
# code in dsPIC assembly) built with avr-gcc,
# whose `int` is 16 bits like XC16's, against one volatile word for the
# chip's registers (bench/ram_image.c). RAM is the image's .data and .bss
# without its constants (avr-gcc copies those to RAM; XC16 leaves them in
# flash). Prints "name bytes" lines: the total, then its parts.
# Usage: bench/firmware_ram.sh BUILD_DIR        (run from the repository root)
set -euo pipefail
out=$1/bench-ram
mkdir -p "$out"
flags=(-std=gnu99 -Os -ffreestanding -mmcu=atmega1284p -I. -Ivm -Inative_functions
       -DDSPIC30_SIMULATED_REGISTERS '-DTARGET_CONFIG="boards/epuck_dspic30/epuck_dspic30_config.h"')

sources=()
# (MAKEFLAGS emptied: run from make, the inner make must not look for its jobs.)
for source in $(MAKEFLAGS= make -s --no-print-directory sources-DSPIC30_APPLICATION); do
    # The DSP-engine kernel needs XC16's builtins (the portable one stands
    # for it); the reset code and the camera's timed row read are dsPIC
    # assembly (ram_image.c stands for the latter).
    [[ $source == ports/dspic30/dspic30_dsp_kernel.c || $source == boards/epuck_dspic30/dspic30_camera_row.c ||
       $source == *.s ]] && continue
    sources+=("$source")
done
sources+=(native_functions/nat_dsp_kernel.c bench/ram_image.c)

avr-gcc "${flags[@]}" -ffunction-sections -fdata-sections -Wl,--gc-sections \
    -Wl,-Map="$out/firmware.map" "${sources[@]}" -o "$out/firmware.elf"

# Input sections of the image's .data and .bss, as the map lists them (a
# long name puts its address and size on the next line).
awk '
function hex(text,  i, value) {
    text = tolower(substr(text, 3)); value = 0
    for (i = 1; i <= length(text); i++)
        value = value * 16 + index("0123456789abcdef", substr(text, i, 1)) - 1
    return value
}
/^\.data|^\.bss/ { output = $1; next }
/^\.[a-z]/ { output = "" }
output != "" && /^ [.A-Z]/ {
    name = $1
    if (NF >= 3 && $2 ~ /^0x/) size = $3
    else { getline; if ($1 !~ /^0x/) next; size = $2 }
    if (name !~ /^\.rodata/) ram += hex(size)
}
END { printf "total %d\n", ram }' "$out/firmware.map"

# The parts, sized by bench/ram_parts.c as avr-gcc lays them out.
avr-gcc "${flags[@]}" -c bench/ram_parts.c -o "$out/parts.o"
avr-nm -S -t d "$out/parts.o" | awk '$4 ~ /^ram_part_/ { sub(/^ram_part_/, "", $4); print $4, $2 + 0 }'
