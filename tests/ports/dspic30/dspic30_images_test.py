#!/usr/bin/env python3
"""The e-puck's dsPIC30 images (`make dspic30`) and the checks that guard
them (scripts/check-dspic30-images.py): the images as built pass, and each
defect the checks exist for, made on purpose in a copy (a changed word, a
lost bootloader, a vector that leads elsewhere, code linked into the
bytecode store, an undefined symbol, an image too large for its region, a
missing or foreign compiler), is refused with a message that names it.

Run from the repository's root after `make dspic30` (make test does both);
ends with "N passed, N failed".
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile

OUT = "build/dspic30"
CHECK = "scripts/check-dspic30-images.py"
EPUCK_IMAGE = "build/host/bin/epuck-image"
results = {"passed": 0, "failed": 0}
# Every temporary folder of the run, removed at its end.
scratch = tempfile.mkdtemp(prefix="dspic30-images-test-")


def make_variable(name):
    environment = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS")}
    return subprocess.run(["make", "-s", "--no-print-directory", f"print-{name}"], check=True,
                          capture_output=True, text=True, env=environment).stdout.strip()


PREFIX = make_variable("DSPIC_PREFIX")
LINK_FLAGS = ["-mcpu=30F6014A", "-nostartfiles", "-nostdlib"]
LINK_OPTIONS = "--no-pack-data,--no-isr,--no-ivt"


def test(name):
    def run(function):
        try:
            function()
            results["passed"] += 1
            print(f"ok   {name}")
        except AssertionError as error:
            results["failed"] += 1
            print(f"FAIL {name}: {error}")
        return function
    return run


def check(folder):
    """The checker on a folder of images: (exit status, its messages)."""
    done = subprocess.run([CHECK, PREFIX, folder, EPUCK_IMAGE], capture_output=True, text=True)
    return done.returncode, done.stdout + done.stderr


def copy_of_images():
    folder = tempfile.mkdtemp(dir=scratch)
    for name in os.listdir(OUT):
        if name.endswith((".elf", ".hex")):
            shutil.copy(f"{OUT}/{name}", folder)
    return folder


def link(image, script, extra_objects=(), extra_options=""):
    """Links an image's objects again with another script; (status, messages, folder)."""
    folder = copy_of_images()
    objects = make_variable(f"DSPIC30_{image.upper()}_OBJECTS").split()
    options = LINK_OPTIONS + (",--gc-sections,--no-handles" if image == "bootloader" else "")
    elf = f"{folder}/epuck-aseba-{image}.elf"
    done = subprocess.run([PREFIX + "gcc", *LINK_FLAGS, f"-Wl,--script={script},{options}"
                           + extra_options, *objects, *extra_objects, "-o", elf],
                          capture_output=True, text=True)
    if done.returncode == 0:
        subprocess.run([PREFIX + "bin2hex", elf], check=True, capture_output=True)
    return done.returncode, done.stdout + done.stderr, folder


def script_variant(path, old, new):
    with open(path) as file:
        text = file.read()
    assert old in text, f"{path} no longer holds {old!r}"
    handle, variant = tempfile.mkstemp(suffix=".gld", dir=scratch)
    with os.fdopen(handle, "w") as file:
        file.write(text.replace(old, new))
    return variant


def replace_hex_word(path, pc, value):
    """Rewrites the instruction at PC address `pc` in a Microchip HEX file."""
    lines, upper = [], 0
    with open(path) as file:
        for line in file:
            line = line.strip()
            data = bytes.fromhex(line[1:])
            count, offset, kind = data[0], data[1] << 8 | data[2], data[3]
            if kind == 4:
                upper = data[4] << 8 | data[5]
            elif kind == 0:
                start = (upper << 16 | offset) // 2
                body = bytearray(data[4:4 + count])
                for i in range(0, count, 4):
                    if start + i // 2 == pc:
                        body[i:i + 3] = bytes((value & 0xFF, value >> 8 & 0xFF, value >> 16))
                record = bytes((count,)) + data[1:4] + bytes(body)
                line = ":" + (record + bytes(((-sum(record)) & 0xFF,))).hex().upper()
            lines.append(line)
    with open(path, "w") as file:
        file.write("\n".join(lines) + "\n")


@test("the images as built pass every check")
def images_pass():
    status, messages = check(OUT)
    assert status == 0, messages
    assert "images checked" in messages, messages


@test("a changed word of the application image is found")
def changed_word():
    folder = copy_of_images()
    replace_hex_word(f"{folder}/epuck-aseba.hex", 0x0300, 0x123456)
    status, messages = check(folder)
    assert status == 1 and "epuck-aseba.hex" in messages and "differ" in messages, messages


@test("a factory image without the bootloader is found")
def factory_without_bootloader():
    folder = copy_of_images()
    shutil.copy(f"{folder}/epuck-aseba.hex", f"{folder}/epuck-aseba-factory.hex")
    status, messages = check(folder)
    assert status == 1 and "epuck-aseba-factory.hex" in messages, messages


@test("an interrupt vector that does not lead to the GOTO table is found")
def wrong_vector():
    script = script_variant("linker/epuck-bootloader.gld",
                            "LONG(APPLICATION_TABLE_BASE + TABLE_SLOT_SPAN * 18); /* U1RXInterrupt */",
                            "LONG(APPLICATION_TABLE_BASE + TABLE_SLOT_SPAN * 19); /* U1RXInterrupt */")
    status, messages, folder = link("bootloader", script)
    assert status == 0, messages
    status, messages = check(folder)
    assert status == 1 and "IVT entry 17 (U1RXInterrupt)" in messages, messages


@test("code linked into the bytecode store is found")
def code_in_the_store():
    script = script_variant("linker/epuck-app.gld", "  .text CODE_BASE :",
                            "  .misplaced BYTECODE_STORE_BASE : { *(.text.epuck_rc5_init); } "
                            ">bytecode_store\n  .text CODE_BASE :")
    # Its calls cannot reach so far either: linked all the same, to be checked.
    status, messages, folder = link("application", script, extra_options=",--noinhibit-exec")
    status, messages = check(folder)
    assert status == 1 and "section .misplaced" in messages and "outside" in messages, messages


@test("an undefined symbol is found")
def undefined_symbol():
    folder = tempfile.mkdtemp(dir=scratch)
    with open(f"{folder}/uses.c", "w") as file:
        file.write("extern int not_defined_anywhere;\nint uses(void) { return not_defined_anywhere; }\n")
    subprocess.run([PREFIX + "gcc", "-mcpu=30F6014A", "-ffreestanding", "-c", f"{folder}/uses.c",
                    "-o", f"{folder}/uses.o"], check=True)
    status, messages, images = link("application", "linker/epuck-app.gld", [f"{folder}/uses.o"],
                                    ",--noinhibit-exec")
    status, messages = check(images)
    assert status == 1 and "_not_defined_anywhere is undefined" in messages, messages


@test("an image too large for its region names the region and the overflow in bytes")
def overflow():
    script = script_variant("linker/epuck-app.gld",
                            "program (xr)     : ORIGIN = 0x000200, LENGTH = 0x016140",
                            "program (xr)     : ORIGIN = 0x000200, LENGTH = 0x001000")
    objects = make_variable("DSPIC30_APPLICATION_OBJECTS").split()
    done = subprocess.run([CHECK, "--overflow", PREFIX, script, "program", *objects],
                          capture_output=True, text=True)
    match = re.search(r"does not fit region program .* (\d+) bytes too many", done.stderr)
    assert done.returncode == 1 and match and int(match.group(1)) > 0, done.stderr


@test("make dspic30 without a dsPIC compiler names both ways to get one")
def no_compiler():
    done = subprocess.run(["make", "-s", "dspic30-toolchain", "DSPIC_TOOLCHAIN=/nonexistent"],
                          capture_output=True, text=True,
                          env={k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS")})
    assert done.returncode != 0, done.stderr
    assert "XC16" in done.stderr and "DSPIC_TOOLCHAIN" in done.stderr, done.stderr


@test("a host compiler given as the dsPIC toolchain is named as such")
def foreign_compiler():
    host_gcc = shutil.which("gcc")
    done = subprocess.run(["make", "-s", "dspic30-toolchain", f"DSPIC_TOOLCHAIN={host_gcc}"],
                          capture_output=True, text=True,
                          env={k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS")})
    assert done.returncode != 0 and "not a dsPIC toolchain" in done.stderr, done.stderr


shutil.rmtree(scratch, ignore_errors=True)
print(f"{results['passed']} passed, {results['failed']} failed")
sys.exit(1 if results["failed"] else 0)
