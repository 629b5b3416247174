#!/usr/bin/env python3
"""Program memory and RAM of the e-puck's dsPIC30 images, from what the
dsPIC linker wrote (`make dspic30`): the map files' input sections by the
object they come from, and the RAM's parts sized by the dsPIC compiler.

Usage: bench/dspic30_sizes.py BUILD_DIR TOOLCHAIN_PREFIX   (from the repository root)

Prints "name value" lines for scripts/bench.sh:
  program memory, in instruction words (a 24-bit word is 2 PC units; the
  paper counts 3 bytes per word): code_<part> and const_<part> for each part
  below, the whole application (application_code, application_const) and
  the bootloader image (bootloader_code, bootloader_const);
  RAM, in bytes: ram_total (.nbss and .ndata of the application), ram_stack
  (what the linker leaves for the stack) and the parts of bench/ram_parts.c.
"""

import re
import subprocess
import sys

# Parts of the application, by the path of the object an input section
# comes from; the first pattern that matches names the part.
PARTS = [
    ("vm", r"/vm/vm[a-z_]*\.o$"),
    ("node", r"/vm/node[a-z_]*\.o$"),
    ("dsp_natives", r"/(native_functions/nat_dsp[a-z_]*|ports/dspic30/dspic30_dsp_kernel)\.o$"),
    ("natives", r"/native_functions/nat_[a-z_]*\.o$"),
    # The main loop and the robot's package (description, native table).
    ("firmware", r"/(firmware|robots/[a-z0-9_]+)/[a-z_]*\.o$"),
    ("drivers", r"/robots/[a-z0-9_]+/devices/[a-z_]*\.o$"),
    ("store", r"/(store|bootloader)/[a-z_]*\.o$"),
    ("runtime", r"/ports/dspic30/dspic30_(reset|startup|runtime)\.o$"),
    # The chip, the board on it, and the link rings of the boundary.
    ("port", r"/(ports|boards|hal)/[a-z_/0-9]*\.o$"),
]
# Anything else: the linker's own sections (the jump table of function
# pointers, "jump_table"), named "other".


def sections_by_object(map_path):
    """(output section, object path) -> PC units, from a dsPIC linker map."""
    sizes = {}
    output = None
    pending = None
    with open(map_path, encoding="latin-1") as file:
        for line in file:
            heading = re.match(r"^(\.[a-z_]+)\s+0x[0-9a-f]+\s+0x[0-9a-f]+", line)
            if heading:
                output = heading.group(1)
                continue
            if line.startswith(".") or line.startswith("__"):
                output = None
            if output is None:
                continue
            # " .text.name  0xADDRESS  0xSIZE object", or the name alone on
            # its line and the rest on the next.
            fields = line.split()
            if len(fields) == 1 and line.startswith(" ."):
                pending = fields[0]
                continue
            if pending and len(fields) == 3 and fields[0].startswith("0x"):
                fields = [pending] + fields
            pending = None
            if len(fields) == 4 and line.startswith(" ") and fields[1].startswith("0x") \
                    and fields[2].startswith("0x"):
                key = (output, fields[3])
                sizes[key] = sizes.get(key, 0) + int(fields[2], 16)
    return sizes


def part_of(path):
    for name, pattern in PARTS:
        if re.search(pattern, path):
            return name
    return "other"


def memory_report(map_path, region):
    """(code, constants) of a map's region report, in PC units."""
    with open(map_path, encoding="latin-1") as file:
        text = file.read()
    code = sum(int(size, 16) for size in re.findall(r"^\.(?:text|init|isr)\S*\s+0x[0-9a-f]+\s+(0x[0-9a-f]+)", text, re.M)[:1])
    const = sum(int(size, 16) for size in re.findall(r"^\.(?:const|dinit)\s+0x[0-9a-f]+\s+(0x[0-9a-f]+)", text, re.M)[:2])
    return code, const


def main():
    build, prefix = sys.argv[1], sys.argv[2]
    out = f"{build}/dspic30"
    sizes = sections_by_object(f"{out}/epuck-aseba-application.map")
    totals = {}
    for (output, path), pc_units in sizes.items():
        kind = "const" if output == ".const" else "code" if output in (".text", ".init") else None
        if kind:
            key = f"{kind}_{part_of(path)}"
            totals[key] = totals.get(key, 0) + pc_units
    for name, _ in PARTS + [("other", "")]:
        for kind in ("code", "const"):
            print(f"{kind}_{name} {totals.get(f'{kind}_{name}', 0) // 2}")
    for image in ("application", "bootloader"):
        code, const = memory_report(f"{out}/epuck-aseba-{image}.map", "program")
        print(f"{image}_code {code // 2}")
        print(f"{image}_const {const // 2}")

    symbols = {}
    for line in subprocess.run([prefix + "nm", f"{out}/epuck-aseba-application.elf"],
                               check=True, capture_output=True, text=True).stdout.splitlines():
        fields = line.split()
        if len(fields) == 3:
            symbols[fields[2]] = int(fields[0], 16)
    ram = sum(size for (output, _), size in sizes.items() if output in (".nbss", ".ndata", ".bss", ".data"))
    print(f"ram_total {ram}")
    print(f"ram_stack {symbols['__SPLIM_init'] - symbols['__SP_init'] + 2}")

    # The parts, as the dsPIC compiler lays them out.
    parts_object = f"{out}/ram_parts.o"
    subprocess.run([prefix + "gcc", "-mcpu=30F6014A", "-std=gnu99", "-Os", "-ffreestanding",
                    "-I.", "-Ivm", "-Inative_functions",
                    '-DTARGET_CONFIG="boards/epuck_dspic30/epuck_dspic30_config.h"',
                    "-c", "bench/ram_parts.c", "-o", parts_object], check=True)
    for line in subprocess.run([prefix + "objdump", "-t", parts_object], check=True,
                               capture_output=True, text=True).stdout.splitlines():
        match = re.search(r"\s([0-9a-f]+)\s+_ram_part_(\w+)$", line)
        if match:
            print(f"{match.group(2)} {int(match.group(1), 16)}")


if __name__ == "__main__":
    main()
