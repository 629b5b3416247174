#!/usr/bin/env python3
"""The firmware's layers, and a check that no file includes a higher one.

Every `#include "..."` of the firmware's C sources (the folders below) is
read; an include of a file of a higher layer fails the check, as does an
include between two folders of one layer that must not know each other (one
chip's port and another's, two boards, two robots). Includes named by the
target's configuration (`#include TARGET_CONFIG`, `#include ROBOT_HEADER`)
are how the lower layers reach what a target chose, and are not read.

    scripts/check-layers.py            the check; ends with "N passed, N failed"
    scripts/check-layers.py --list     every file with its layer

docs/architecture.md draws the same layers.
"""

import fnmatch
import pathlib
import re
import sys

# Lowest first: a file may include files of its own layer and of the layers
# above it in this list. A pattern ending in "/" is a folder (its files and
# subfolders); "*" is one folder name. With `separate`, the folders a "*"
# stands for (each chip, each board, each robot) may not include each other.
# A file takes the last layer whose pattern matches it.
LAYERS = [
    ("vm", ["vm/"], False),  # the VM and the protocol-5 node
    ("native functions", ["native_functions/"], False),
    ("hal", ["hal/"], False),  # the chip-neutral boundary
    ("chip", ["ports/*/"], True),  # a chip's registers, peripherals, start-up
    ("store", ["store/"], False),  # the bytecode store
    ("bootloader", ["bootloader/"], False),
    ("robot", ["robots/*/"], True),  # a robot's description, natives, devices
    ("firmware", ["firmware/"], False),  # the robot-neutral main loop
    ("board", ["boards/*/"], True),  # a robot on a chip: configuration, pins
    ("image", ["ports/*/*_main.c", "ports/host/"], True),  # the entry points
]

SOURCE_SUFFIXES = {".c", ".h", ".s"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def matches(path, pattern):
    """Whether `path` (relative, with /) falls under `pattern`; returns the
    folder a "*" of the pattern stands for ("" when it has none), or None."""
    parts = pattern.rstrip("/").split("/")
    folder = pattern.endswith("/")
    names = path.split("/")
    if len(names) < len(parts) + (1 if folder else 0) or (not folder and len(names) != len(parts)):
        return None
    unit = []
    for name, part in zip(names, parts):
        if not fnmatch.fnmatchcase(name, part):
            return None
        if "*" in part:
            unit.append(name)
    return "/".join(unit)


def layer_of(path):
    """(index, unit) of the layer `path` belongs to, or None."""
    found = None
    for index, (_, patterns, separate) in enumerate(LAYERS):
        for pattern in patterns:
            unit = matches(path, pattern)
            if unit is not None:
                found = (index, unit if separate else "")
    return found


def resolve(root, source, included):
    """The repository path an include names: from the including file's
    folder first, as the compilers look, then from the root (-I.), then from
    the folders of -Ivm -Inative_functions."""
    for base in (source.parent, root, root / "vm", root / "native_functions"):
        candidate = (base / included).resolve()
        if candidate.is_file():
            return candidate.relative_to(root).as_posix()
    return None


def sources(root):
    for pattern in {p.split("*")[0].rstrip("/") or "." for _, ps, _ in LAYERS for p in ps}:
        base = root / pattern
        if base.is_file():
            yield base
        elif base.is_dir():
            yield from (p for p in base.rglob("*") if p.suffix in SOURCE_SUFFIXES)


def problem(source, target):
    """Why `source` may not include `target` (repository paths), or None."""
    here, there = layer_of(source), layer_of(target)
    if here is None or there is None:
        return None
    if there[0] > here[0]:
        return f"{LAYERS[here[0]][0]} includes {target}, of the higher layer {LAYERS[there[0]][0]}"
    if there[0] == here[0] and here[1] != there[1]:
        return f"{LAYERS[here[0]][0]} {here[1]} includes {target}, of another {LAYERS[there[0]][0]} ({there[1]})"
    return None


# The check's own cases: (including file, included file, whether refused).
SELF_CHECKS = [
    ("robots/epuck/devices/epuck_devices.h", "firmware/firmware.h", True),
    ("ports/dspic30/dspic30_chip.h", "robots/epuck/epuck_board.h", True),
    ("boards/epuck_host/epuck_host_config.h", "ports/dspic30/dspic30_flash_geometry.h", False),
    ("boards/epuck_host/host_board.h", "boards/epuck_dspic30/epuck_dspic30_board.h", True),
    ("ports/stm32f4/stm32f4_clock.c", "ports/dspic30/dspic30_chip.h", True),
    ("ports/dspic30/dspic30_application_main.c", "firmware/firmware.h", False),
    ("ports/dspic30/dspic30_uart.c", "ports/dspic30/dspic30_application_main.c", True),
    ("store/bytecode_store.c", "vm/node_crc.h", False),
    ("vm/vm.h", "hal/hal.h", True),
]


def main(argv):
    root = pathlib.Path(__file__).resolve().parent.parent
    files = sorted(set(sources(root)))
    if "--list" in argv:
        for path in files:
            relative = path.relative_to(root).as_posix()
            layer = layer_of(relative)
            print(f"{LAYERS[layer[0]][0] if layer else '-':18} {relative}")
        return 0
    checked = 0
    problems = []
    for source, target, refused in SELF_CHECKS:
        checked += 1
        if (problem(source, target) is not None) != refused:
            problems.append(f"check-layers itself: {source} including {target} should be "
                            f"{'refused' if refused else 'allowed'}")
    for path in files:
        relative = path.relative_to(root).as_posix()
        if layer_of(relative) is None:
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            checked += 1
            target = resolve(root, path, match.group(1))
            if target is None:
                problems.append(f"{relative}:{number}: includes {match.group(1)}, which is not in the repository")
                continue
            why = problem(relative, target)
            if why:
                problems.append(f"{relative}:{number}: {why}")
    for line in problems:
        print(line)
    print(f"check-layers: {checked - len(SELF_CHECKS)} includes of {len(files)} files, "
          f"and {len(SELF_CHECKS)} cases of its own")
    print(f"{checked - len(problems)} passed, {len(problems)} failed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
