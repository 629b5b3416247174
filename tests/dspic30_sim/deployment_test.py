#!/usr/bin/env python3
"""Deployment on the e-puck's real machine code: `make dspic30`'s images run
on dspic30-sim as an Aseba node on a TCP port (--uart1 tcp:0), driven by the
project's console and the reference asebamassloader as they drive a robot
over Bluetooth.

1. The console's `aseba flash` writes the application into a robot running
   the factory image, through UART1 and the Aseba bootloader; the robot
   reboots into it and answers LIST_NODES, and its flash then holds the
   HEX file's words (read from the --memory file).
2. The same into a robot holding only the bootloader (no application: it
   waits in its bootloader and is flashed by id); it then answers as a node.
3. A program loaded with `aseba load` and stored with `aseba save` survives
   a restart of the simulator with --memory: at boot it sets the variables
   its source says.
4. asebamassloader (the reference tool) loads a project into it.

Run from the repository's root; ends with "N passed, N failed".
"""

import os
import subprocess
import sys
import tempfile
import time

from sim_node import (APPLICATION_IMAGE, BOOTLOADER_IMAGE, FACTORY_IMAGE, Node, Results, boot,
                      console, hex_words, memory_flash, node_present, nvm_operations,
                      wait_for_node)

STORED_PROGRAM = "leftSpeed = 321\nrightSpeed = -57\n"
# Where no bootloader waits on a host: as fast as the host can.
FAST = ["--speed", "0"]
MASSLOADER_PROJECT = """<!DOCTYPE aesl-source>
<network>
<keywords flag="true"/>
<node nodeId="1" name="e-puck">leftSpeed = 44
</node>
</network>
"""


def flash_into_factory_robot(results, folder):
    memory = os.path.join(folder, "factory.memory")
    node = Node(memory, FACTORY_IMAGE)
    try:
        results.check(wait_for_node(node) is not None,
                      "the factory image answers `aseba nodes` on its TCP port")
        started = time.monotonic()
        status, output = console(node, "flash", APPLICATION_IMAGE)
        seconds = time.monotonic() - started
        results.check(status == 0, f"`aseba flash` of the application through UART1 and the "
                      f"bootloader ({seconds:.1f} s)", output)
        status, output = console(node, "nodes")
        results.check(status == 0 and "e-puck" in output,
                      "after the flashing the robot answers as a node again", output)
    finally:
        _, stderr = node.stop()
    operations = nvm_operations(stderr)
    results.check(operations is not None and operations > 0,
                  f"the flashing erased and wrote flash rows ({operations} NVM operations)", stderr)
    flash = memory_flash(memory)
    expected = hex_words(APPLICATION_IMAGE)
    wrong = [pc for pc, word in expected.items() if flash[pc] != word]
    results.check(not wrong, f"the robot's flash holds the {len(expected)} words of "
                  f"{APPLICATION_IMAGE}", f"first differences at {[hex(pc) for pc in wrong[:8]]}")


def flash_into_bare_bootloader(results, folder):
    memory = os.path.join(folder, "bootloader.memory")
    # The robot's clock at 4 x the wall clock: a flashing takes a quarter of
    # its time, the bootloader's one-second wait stays ample for the console.
    node = Node(memory, BOOTLOADER_IMAGE, ["--speed", "4"])
    try:
        time.sleep(0.5)  # the bootloader's second: no application to start
        status, output = console(node, "nodes")
        results.check("e-puck" not in output,
                      "a robot with only the bootloader does not answer as a node", output)
        status, output = console(node, "flash", APPLICATION_IMAGE, "--node", "1")
        results.check(status == 0, "`aseba flash --node 1` writes the application into it",
                      output)
        results.check(wait_for_node(node) is not None, "it then starts the application and "
                      "answers as a node")
    finally:
        node.stop()
    status, replies = boot(memory)
    results.check(node_present(replies) == [1], "it boots into the application from its "
                  "memory file and answers LIST_NODES", f"exit {status}, {replies}")


def stored_program_survives_restart(results, folder):
    memory = os.path.join(folder, "store.memory")
    program = os.path.join(folder, "store.aseba")
    with open(program, "w") as text:
        text.write(STORED_PROGRAM)
    node = Node(memory, FACTORY_IMAGE, FAST)
    try:
        results.check(wait_for_node(node, home=folder) is not None, "the robot is up")
        status, output = console(node, "load", program, home=folder)
        results.check(status == 0, "`aseba load` of a program", output)
        status, output = console(node, "save", home=folder)
        results.check(status == 0, "`aseba save` asks the robot to store it", output)
        time.sleep(1)  # the robot does not confirm: give the store its rows
    finally:
        node.stop()

    node = Node(memory, FACTORY_IMAGE, FAST)  # the memory file exists: the image is not loaded
    try:
        results.check(wait_for_node(node, home=folder) is not None,
                      "after a restart with the same --memory the robot answers again")
        status, output = console(node, "vars", "leftSpeed", "rightSpeed", home=folder)
        results.check(status == 0 and "321" in output and "-57" in output,
                      "the stored program ran at boot: leftSpeed = 321, rightSpeed = -57",
                      output)
    finally:
        _, stderr = node.stop()
    results.check("is not loaded" in stderr, "the simulator says the image was not loaded",
                  stderr)


def massloader_loads(results, folder):
    project = os.path.join(folder, "massloader.aesl")
    with open(project, "w") as text:
        text.write(MASSLOADER_PROJECT)
    node = Node(os.path.join(folder, "massloader.memory"), FACTORY_IMAGE, FAST)
    try:
        wait_for_node(node, home=folder)
        environment = dict(os.environ, LANG="en_US.UTF-8")
        run = subprocess.run(["asebamassloader", "--once", project, node.target],
                             capture_output=True, timeout=60, env=environment)
        output = (run.stdout + run.stderr).decode(errors="replace")
        results.check(run.returncode == 0 and "bytecodes loaded to target e-puck" in output,
                      "asebamassloader --once loads a project into it", output)
        status, output = console(node, "vars", "leftSpeed", home=folder)
        results.check(status == 0 and "44" in output, "the loaded program runs: leftSpeed = 44",
                      output)
    finally:
        node.stop()


def main():
    results = Results()
    with tempfile.TemporaryDirectory() as folder:
        flash_into_factory_robot(results, folder)
        flash_into_bare_bootloader(results, folder)
        stored_program_survives_restart(results, folder)
        massloader_loads(results, folder)
    return results.finish()


if __name__ == "__main__":
    sys.exit(main())
