"""What the deployment tests of dspic30-sim share: the simulated e-puck as
an Aseba node on a TCP port (--uart1 tcp:0), the console run against it, a
boot from a memory file checked on standard input and output, and readers
of Intel HEX files and of the simulator's memory file.

Expected values come from the Aseba protocol 5 (message types), the
bootloader's documented protocol and the HEX files `make dspic30` writes,
never from the simulator.
"""

import os
import shutil
import signal
import struct
import subprocess
import tempfile
import time

SIMULATOR = "build/host/bin/dspic30-sim"
CONSOLE = "build/host/bin/aseba"
FACTORY_IMAGE = "build/dspic30/epuck-aseba-factory.hex"
# The application with its descriptor, as the console's flash command takes it.
APPLICATION_IMAGE = "build/dspic30/epuck-aseba.hex"
BOOTLOADER_IMAGE = "build/dspic30/epuck-aseba-bootloader.hex"

LIST_NODES, NODE_PRESENT, PROTOCOL_VERSION = 0xA011, 0x900C, 5
BOOTLOADER_DESCRIPTION = 0x8004
CHIP_HZ = 14_745_600
FLASH_WORDS = 48 * 1024


def frames(data):
    """(source, type, payload) of each frame: length, source, type, then the payload."""
    found = []
    while len(data) >= 6:
        length, source, kind = struct.unpack_from("<HHH", data)
        found.append((source, kind, data[6:6 + length]))
        data = data[6 + length:]
    return found


class Node:
    """dspic30-sim with UART1 on a free loopback port; stop() ends it as
    Ctrl-C would (the memory file is written) and returns its standard error."""

    def __init__(self, memory, image=None, extra=()):
        command = [SIMULATOR, "--uart1", "tcp:0", "--memory", memory, *extra]
        if image:
            command.append(image)
        self.process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        line = self.process.stdout.readline().decode()
        prefix = "dspic30-sim: UART1 on tcp:localhost;"
        if not line.startswith(prefix):
            self.process.kill()
            raise RuntimeError(f"no port announced: {line!r} "
                               f"{self.process.stderr.read().decode(errors='replace')}")
        self.port = int(line[len(prefix):])
        self.target = f"tcp:localhost;{self.port}"

    def wait(self, timeout):
        """Waits for the simulator to end by itself (a power cut); its exit
        status and standard error, or None when it is still running."""
        try:
            self.process.wait(timeout)
        except subprocess.TimeoutExpired:
            return None
        return self.process.returncode, self.process.stderr.read().decode(errors="replace")

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
        self.process.wait(30)
        return self.process.returncode, self.process.stderr.read().decode(errors="replace")


def console(node, *arguments, timeout=120, home=None):
    """Runs the console against `node`; (exit status, output)."""
    environment = dict(os.environ)
    if home:
        environment["HOME"] = home
        environment.pop("XDG_STATE_HOME", None)
    run = subprocess.run([CONSOLE, "-t", node.target, *arguments], capture_output=True,
                         timeout=timeout, env=environment)
    return run.returncode, (run.stdout + run.stderr).decode(errors="replace")


def wait_for_node(node, seconds=20, home=None):
    """Polls `aseba nodes` until the robot answers as a node (it starts
    about a second after reset, after its bootloader's wait)."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        # A short wait for answers: the robot answers within milliseconds
        # once it is up.
        status, output = console(node, "--timeout", "250", "nodes", home=home)
        if status == 0 and "e-puck" in output:
            return output
        time.sleep(0.1)
    return None


def boot(memory, speak_after=30_000_000, run_cycles=80_000_000):
    """Boots a copy of `memory` with UART1 on standard input and output, as
    fast as the host can, sends LIST_NODES once the bootloader's second is
    over and returns the frames the robot sent."""
    with tempfile.TemporaryDirectory() as folder:
        copy = os.path.join(folder, "memory")
        shutil.copy(memory, copy)
        request = struct.pack("<HHHH", 2, 0, LIST_NODES, PROTOCOL_VERSION)
        run = subprocess.run([SIMULATOR, "--memory", copy, "--input-after", str(speak_after),
                              "--cycles", str(run_cycles)], input=request, capture_output=True,
                             timeout=120)
        return run.returncode, frames(run.stdout)


def node_present(replies):
    return [source for source, kind, payload in replies
            if kind == NODE_PRESENT and struct.unpack("<H", payload[:2])[0] == PROTOCOL_VERSION]


def bootloader_waiting(replies):
    return any(kind == BOOTLOADER_DESCRIPTION for _, kind, _ in replies)


def hex_words(path):
    """PC address -> 24-bit word of a Microchip Intel HEX file (byte address
    = 2 x PC, 4 bytes a word, the fourth 0); only flash (below 0x18000)."""
    memory = {}
    upper = 0
    with open(path) as text:
        for line in text:
            line = line.strip()
            if not line.startswith(":"):
                continue
            record = bytes.fromhex(line[1:])
            count, address, kind = record[0], (record[1] << 8) | record[2], record[3]
            data = record[4:4 + count]
            if kind == 4:
                upper = (data[0] << 8) | data[1]
            elif kind == 0:
                for i, byte in enumerate(data):
                    memory[(upper << 16) + address + i] = byte
    words = {}
    for byte_address in memory:
        base = byte_address & ~3
        pc = base // 2
        if pc < 2 * FLASH_WORDS and pc not in words:
            words[pc] = sum(memory.get(base + i, 0xFF) << (8 * i) for i in range(3))
    return words


def memory_flash(path):
    """The flash words of a memory file, by PC address: after its header
    line, 3 bytes a word, little-endian (docs/dspic30-sim.md)."""
    with open(path, "rb") as data:
        content = data.read()
    start = content.index(b"\n") + 1
    return {2 * i: int.from_bytes(content[start + 3 * i:start + 3 * i + 3], "little")
            for i in range(FLASH_WORDS)}


def nvm_operations(stderr):
    """The NVM operation count the simulator prints when it writes its memory file."""
    for line in stderr.splitlines():
        if "NVM operations; memory kept in" in line:
            return int(line.split("dspic30-sim: ")[1].split()[0])
    return None


class Results:
    """ok/FAIL lines, then "N passed, N failed"."""

    def __init__(self):
        self.passed = self.failed = 0

    def check(self, ok, text, detail=""):
        if ok:
            self.passed += 1
            print(f"ok   {text}", flush=True)
        else:
            self.failed += 1
            print(f"FAIL {text}\n{detail}", flush=True)
        return ok

    def finish(self):
        print(f"{self.passed} passed, {self.failed} failed")
        return 0 if self.failed == 0 else 1
