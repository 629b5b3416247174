#!/usr/bin/env python3
"""The last step of `make dspic30`: the e-puck's images checked against the
programs the dsPIC linker wrote, before they are kept.

Usage: check-dspic30-images.py TOOLCHAIN_PREFIX OUT_DIR EPUCK_IMAGE
       check-dspic30-images.py --overflow TOOLCHAIN_PREFIX SCRIPT REGION OBJECT...

TOOLCHAIN_PREFIX is the path of the toolchain's programs without their last
word (build/toolchains/pic30-elf/bin/pic30-elf-, or XC16's .../bin/xc16-);
OUT_DIR holds epuck-aseba-application.elf/.hex, epuck-aseba-bootloader.elf/.hex,
epuck-aseba.hex and epuck-aseba-factory.hex. Each check compares two
independent readings: the linked programs as the toolchain's own objdump
and nm show them, and the HEX files as epuck-image reads them (its `dump`).

Checked:
  - no symbol is left undefined (but the linker's own, below);
  - every section lies in its region: the application's code and constants
    from CODE_BASE up to DESCRIPTOR_BASE and its GOTO table below, the
    bootloader's in its 64 rows and its vectors in rows 0-3, nothing in the
    Tiny bootloader's rows, data in RAM under the stack;
  - every word of each program is in each HEX file that should hold it, with
    the same value, and nothing else is there but the descriptor and erased
    fill; the descriptor's entry, end and CRC are those of the linked code;
  - the bootloader's reset vector leads to its start-up, its interrupt
    vectors to the application's GOTO table (linker/epuck-app.gld), whose
    slots lead to the application's handlers, or to __DefaultInterrupt.
Prints one line per image, and each failure; exits 1 on any failure.

With --overflow, after a failed link: how far the objects' code and
constants overrun REGION of the linker SCRIPT, in PC units and in bytes (3
per instruction word), since the dsPIC linker only names the sections it
could not place.
"""

import re
import subprocess
import sys

# The flash layout's constants that the linked programs do not carry as
# symbols (robots/epuck/epuck_flash_layout.h, bootloader/boot_application.h).
ROW_SPAN = 0x40
ERASED = 0xFFFFFF
DESCRIPTOR_MAGIC = 0xA5EB01
GOTO_OPCODE = 0x04
GOTO_HIGH_MASK = 0x7F
TABLE_SLOT_SPAN = 4
IVT_ENTRIES = 62
RAM_START, RAM_END = 0x0800, 0x2800
CONFIGURATION_START = 0xF80000
# Symbols the Microchip linker itself names and resolves (its start-up mode
# and reset selection, unused without Microchip's crt0): not ours to define.
LINKER_OWN_SYMBOLS = {"__crt_start_mode_normal", "__resetPRI", "__resetALT"}

failures = []


def fail(image, message):
    failures.append(f"{image}: {message}")


def run(*command):
    return subprocess.run(command, check=True, capture_output=True, text=True).stdout


def symbols(prefix, elf):
    """Defined symbols (name -> value) and undefined names."""
    defined, undefined = {}, set()
    for line in run(prefix + "nm", elf).splitlines():
        fields = line.split()
        if len(fields) == 2 and fields[0] == "U":
            undefined.add(fields[1])
        elif len(fields) == 3:
            defined.setdefault(fields[2], int(fields[0], 16))
    return defined, undefined


class Section:
    def __init__(self, name, size, vma, lma, flags):
        self.name, self.size, self.vma, self.lma, self.flags = name, size, vma, lma, flags

    @property
    def in_program_memory(self):
        return bool({"CODE", "PSV", "READONLY"} & self.flags)

    @property
    def loaded(self):
        return {"CONTENTS", "LOAD"} <= self.flags


def sections(prefix, elf):
    """Allocated sections, from objdump -h (sizes in PC units for program memory)."""
    found = []
    lines = run(prefix + "objdump", "-h", elf).splitlines()
    for header, flags in zip(lines, lines[1:]):
        fields = header.split()
        if len(fields) == 7 and fields[0].isdigit():
            flag_set = {flag.strip() for flag in flags.split(",")}
            if "ALLOC" in flag_set:
                found.append(Section(fields[1], int(fields[2], 16), int(fields[3], 16),
                                     int(fields[4], 16), flag_set))
    return found


def program_words(prefix, elf, section_list):
    """PC address -> 24-bit word of every loaded section in program memory."""
    words = {}
    for section in section_list:
        if not (section.in_program_memory and section.loaded):
            continue
        dump = run(prefix + "objdump", "-s", "-j", section.name, elf)
        psv = "PSV" in section.flags
        for line in dump.splitlines():
            match = re.match(r"^ ([0-9a-f]+) ((?:[0-9a-f]+ ?)+) ", line + " ")
            if not match or line.startswith("Contents"):
                continue
            address = int(match.group(1), 16)
            data = bytes.fromhex(match.group(2).replace(" ", ""))
            if psv:
                # Constants seen through the PSV window: two bytes per
                # instruction word, at the load address, upper byte 0.
                for i in range(0, len(data) - 1, 2):
                    pc = section.lma + (address - section.vma) + i
                    words[pc] = data[i] | data[i + 1] << 8
            else:
                for i in range(0, len(data) - 2, 3):
                    words[address + 2 * (i // 3)] = data[i] | data[i + 1] << 8 | data[i + 2] << 16
    # Configuration words are 16 bits; the HEX file holds no upper byte.
    for pc in words:
        if pc >= CONFIGURATION_START:
            words[pc] &= 0xFFFF
    return words


def hex_words(epuck_image, path):
    """PC address -> word of a HEX file, as epuck-image reads it."""
    words = {}
    for line in run(epuck_image, "dump", path).splitlines():
        address, value = line.split()
        words[int(address, 16)] = int(value, 16)
    return words


def crc16_xmodem(words):
    """CRC-16/XMODEM (polynomial 0x1021, seed 0) of 24-bit words, low byte first."""
    crc = 0
    for word in words:
        for byte in (word & 0xFF, word >> 8 & 0xFF, word >> 16 & 0xFF):
            crc ^= byte << 8
            for _ in range(8):
                crc = (crc << 1 ^ 0x1021 if crc & 0x8000 else crc << 1) & 0xFFFF
    return crc


def goto_target(words, pc):
    first, second = words.get(pc, ERASED), words.get(pc + 2, ERASED)
    if first >> 16 != GOTO_OPCODE or second & ~GOTO_HIGH_MASK:
        return None
    return (first & 0xFFFF) | (second & GOTO_HIGH_MASK) << 16


def check_regions(image, section_list, allowed, defined):
    for section in section_list:
        if section.in_program_memory:
            start, end = section.lma, section.lma + section.size
            if start >= CONFIGURATION_START and section.name.startswith("__F"):
                continue
            if not any(low <= start and end <= high for low, high in allowed):
                fail(image, f"section {section.name} at {start:#08x}-{end:#08x} lies outside "
                            f"its regions ({', '.join(f'{l:#x}-{h:#x}' for l, h in allowed)})")
        else:
            start, end = section.vma, section.vma + section.size
            if not (RAM_START <= start and end <= defined.get("__SP_init", RAM_START)):
                fail(image, f"data section {section.name} at {start:#06x}-{end:#06x} is not "
                            f"in RAM below the stack")
    stack, limit = defined.get("__SP_init"), defined.get("__SPLIM_init")
    if stack is None or limit is None or not RAM_START <= stack < limit < RAM_END:
        fail(image, "no stack inside RAM (__SP_init, __SPLIM_init)")


def overflow(prefix, script, region, objects):
    with open(script) as file:
        match = re.search(rf"^\s*{re.escape(region)}\s*(\([^)]*\))?\s*:\s*ORIGIN\s*=\s*(0x[0-9A-Fa-f]+),"
                          rf"\s*LENGTH\s*=\s*(0x[0-9A-Fa-f]+)", file.read(), re.MULTILINE)
    if not match:
        print(f"dspic30: {script} has no memory region {region}", file=sys.stderr)
        return 1
    origin, length = int(match.group(2), 16), int(match.group(3), 16)
    needed = sum(section.size for path in objects for section in sections(prefix, path)
                 if section.in_program_memory and not section.name.startswith(("__F", ".reset",
                                                                               ".ivt", ".aivt")))
    over = needed - length
    where = f"region {region} of {script} ({origin:#x}-{origin + length:#x}, {length:#x} PC units)"
    if over > 0:
        print(f"dspic30: the image does not fit {where}: its code and constants take "
              f"{needed:#x} PC units, {over:#x} PC units = {(over + 1) // 2 * 3} bytes too many "
              f"(counted before the link drops unused functions, where it does)", file=sys.stderr)
    else:
        print(f"dspic30: the link failed, though the code and constants ({needed:#x} PC units) "
              f"fit {where}: the linker's messages above say why", file=sys.stderr)
    return 1


def main():
    if sys.argv[1] == "--overflow":
        return overflow(sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:])
    prefix, out, epuck_image = sys.argv[1:4]
    application_elf = f"{out}/epuck-aseba-application.elf"
    bootloader_elf = f"{out}/epuck-aseba-bootloader.elf"

    application_symbols, application_undefined = symbols(prefix, application_elf)
    bootloader_symbols, bootloader_undefined = symbols(prefix, bootloader_elf)
    for image, undefined in (("application", application_undefined),
                             ("bootloader", bootloader_undefined)):
        for name in sorted(undefined - LINKER_OWN_SYMBOLS):
            fail(image, f"symbol {name} is undefined")

    a = application_symbols
    b = bootloader_symbols
    table_base, code_base, descriptor = (a["APPLICATION_TABLE_BASE"], a["CODE_BASE"],
                                         a["DESCRIPTOR_BASE"])
    loader_base, tiny_base = b["ASEBA_BOOTLOADER_BASE"], b["TINY_BOOTLOADER_BASE"]
    application_sections = sections(prefix, application_elf)
    bootloader_sections = sections(prefix, bootloader_elf)
    check_regions("application", application_sections,
                  [(table_base, code_base), (code_base, descriptor)], a)
    check_regions("bootloader", bootloader_sections,
                  [(0, table_base), (loader_base, tiny_base)], b)

    # The words of the programs against the words of the HEX files.
    application = program_words(prefix, application_elf, application_sections)
    bootloader = program_words(prefix, bootloader_elf, bootloader_sections)
    for image, elf_words, path in (("application", application, "epuck-aseba-application.hex"),
                                   ("bootloader", bootloader, "epuck-aseba-bootloader.hex")):
        read = hex_words(epuck_image, f"{out}/{path}")
        if read != elf_words:
            differing = sorted(set(read.items()) ^ set(elf_words.items()))[:4]
            fail(image, f"{path} differs from the linked program at "
                        + ", ".join(f"{pc:#08x}" for pc, _ in differing))

    code = {pc: word for pc, word in application.items() if pc < CONFIGURATION_START}
    end = max(code) + 2
    expected_descriptor = [DESCRIPTOR_MAGIC, table_base, end,
                           crc16_xmodem(code.get(pc, ERASED) for pc in range(table_base, end, 2))]
    for path, with_bootloader in (("epuck-aseba.hex", False), ("epuck-aseba-factory.hex", True)):
        read = hex_words(epuck_image, f"{out}/{path}")
        expected = dict(code)
        if with_bootloader:
            expected.update(bootloader)
            expected.update({pc: w for pc, w in application.items() if pc >= CONFIGURATION_START})
        for index, word in enumerate(expected_descriptor):
            expected[descriptor + 2 * index] = word
        wrong = [pc for pc, word in expected.items() if read.get(pc) != word]
        extra = [pc for pc, word in read.items() if pc not in expected and word != ERASED]
        if wrong or extra:
            fail(path, f"{len(wrong)} words differ from the programs and the descriptor "
                       f"(first {min(wrong, default=0):#08x}), {len(extra)} words that no "
                       f"program has (first {min(extra, default=0):#08x})")

    # The vectors: reset, the IVT into the GOTO table, the table into the handlers.
    default = a.get("__DefaultInterrupt", 0)
    if not code_base <= default < descriptor:
        fail("application", "__DefaultInterrupt is not in the application's code")
    if goto_target(bootloader, 0) != b.get("__reset"):
        fail("bootloader", "the reset vector is not a GOTO to its __reset")
    if goto_target(application, table_base) != a.get("__reset"):
        fail("application", "GOTO table slot 0 is not a GOTO to its __reset")
    with open("linker/epuck-app.gld") as script:
        vector_names = re.findall(r"LONG\(0x040000 \| \(__table_(\w+) & 0xFFFF\)\)", script.read())
    if len(vector_names) != IVT_ENTRIES:
        fail("application", f"linker/epuck-app.gld's GOTO table has {len(vector_names)} slots "
                            f"for {IVT_ENTRIES} vectors")
    for k, name in enumerate(vector_names):
        slot = table_base + TABLE_SLOT_SPAN * (1 + k)
        ivt_entry = b["__IVT_BASE"] + 2 * k
        if bootloader.get(ivt_entry) != slot:
            fail("bootloader", f"IVT entry {k} ({name}) does not lead to GOTO table slot {slot:#x}")
        handler = a.get("__" + name, default)
        if goto_target(application, slot) != handler:
            fail("application", f"GOTO table slot {1 + k} ({name}) does not lead to "
                                f"{'_' + name if '__' + name in a else '__DefaultInterrupt'}")

    for failure in failures:
        print(f"check-dspic30-images: {failure}", file=sys.stderr)
    if failures:
        return 1
    print(f"== dsPIC30 images checked: application {len(code)} words up to PC {end:#x} "
          f"(descriptor CRC {expected_descriptor[3]:#06x}), bootloader "
          f"{sum(1 for pc in bootloader if pc < CONFIGURATION_START)} words, "
          f"62 vectors through the GOTO table")
    return 0


if __name__ == "__main__":
    sys.exit(main())
