#!/usr/bin/env python3
"""The e-puck's factory image, as `make dspic30` links it, run from reset on
the dsPIC30F simulator: the Aseba bootloader starts, checks the
application's descriptor and CRC through table reads, jumps to it, and the
application answers a LIST_NODES on UART1 with NODE_PRESENT, protocol 5:
the shipped bytes running as an Aseba node. Expected values are the
protocol's (message types and version of Aseba 1.6), not the firmware's.

Run from the repository's root; ends with "N passed, N failed".
"""

import struct
import subprocess
import sys

SIMULATOR = "build/host/bin/dspic30-sim"
FACTORY_IMAGE = "build/dspic30/epuck-aseba-factory.hex"
LIST_NODES, NODE_PRESENT, PROTOCOL_VERSION = 0xA011, 0x900C, 5
# The bootloader waits about a second (14.7456 million cycles per second)
# before it starts the application: speak after it.
SPEAK_AFTER_CYCLES, RUN_CYCLES = 30_000_000, 80_000_000


def frames(data):
    """(source, type, payload) of each frame: length, source, type, then the payload."""
    found = []
    while len(data) >= 6:
        length, source, kind = struct.unpack_from("<HHH", data)
        found.append((source, kind, data[6:6 + length]))
        data = data[6 + length:]
    return found


def main():
    request = struct.pack("<HHHH", 2, 0, LIST_NODES, PROTOCOL_VERSION)  # from a host, id 0
    run = subprocess.run([SIMULATOR, "--input-after", str(SPEAK_AFTER_CYCLES), "--cycles",
                          str(RUN_CYCLES), FACTORY_IMAGE], input=request, capture_output=True,
                         timeout=300)
    replies = frames(run.stdout)
    present = [(source, payload) for source, kind, payload in replies if kind == NODE_PRESENT]
    ok = run.returncode == 0 and len(present) == 1 and \
        struct.unpack("<H", present[0][1][:2])[0] == PROTOCOL_VERSION
    if ok:
        print(f"ok   the factory image boots through its bootloader and answers LIST_NODES "
              f"as node {present[0][0]}, protocol {PROTOCOL_VERSION}")
    else:
        print(f"FAIL the factory image did not answer LIST_NODES with NODE_PRESENT "
              f"(exit {run.returncode}, frames {[(s, hex(k)) for s, k, _ in replies]}):\n"
              f"{run.stderr.decode(errors='replace')[-2000:]}")
    print(f"{1 if ok else 0} passed, {0 if ok else 1} failed")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
