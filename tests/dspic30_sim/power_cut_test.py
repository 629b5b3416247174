#!/usr/bin/env python3
"""Power cuts on the e-puck's real machine code: dspic30-sim stops as a
power cut would at the K-th NVM operation (--power-cut-at K: that row
operation reaches half its row), keeping its flash in the --memory file;
then the robot is switched on again from that file. Whatever K, it must
boot and answer: as a node (the old or the new application, the old or the
new stored program), or from its bootloader, which waits for a flash and
takes one. Never bricked.

  flash-same  `aseba flash` of the application into a robot holding the same
              application (the factory image: the bootloader skips rows that
              already hold their page and rewrites the descriptor): every K.
  flash-new   the same into a robot holding only the bootloader (every row
              erased and written): K = 1, a third, two thirds, the last
              two (each cut costs a flashing up to it, so a spread), then a
              re-flash after the cut at a third.
  store-odd   `aseba save` of a program over a stored one: every odd K,
  store-even  and every even K (together: every K).

Run from the repository's root with the part to run; ends with "N passed,
N failed".
"""

import os
import re
import shutil
import sys
import tempfile
import time

from sim_node import (APPLICATION_IMAGE, BOOTLOADER_IMAGE, FACTORY_IMAGE, Node, Results, boot,
                      bootloader_waiting, console, node_present, nvm_operations, wait_for_node)

# Simulated time at 4 x the wall clock while the console talks to the robot:
# the bootloader's one-second wait stays a quarter of a second for the
# console, ample, and a flashing takes a quarter of its time.
SPEED = ["--speed", "4"]
# Where no bootloader waits on the console, as fast as the host can.
FAST = ["--speed", "0"]
# The store keeps a program's words up to its last non-zero one: the new
# program (some 120 words) spans three of its blocks, so that cuts fall in
# the erases and writes of a record of several rows.
OLD_PROGRAM = "leftSpeed = 111\n"
NEW_PROGRAM = "leftSpeed = 222\n" + "".join(f"rightSpeed = {i}\n" for i in range(60))


def fresh_memory(folder, name, image):
    """A memory file of a robot that was switched on with `image`."""
    memory = os.path.join(folder, name)
    node = Node(memory, image, SPEED)
    node.stop()
    return memory


def flash_until_cut(memory, cut, flash_arguments):
    """Flashes the robot of `memory` with a power cut at operation `cut`;
    whether the simulator stopped there (its standard error)."""
    node = Node(memory, None, SPEED + ["--power-cut-at", str(cut)])
    try:
        if "--node" not in flash_arguments:
            wait_for_node(node)
        else:
            time.sleep(0.5)
        console(node, "flash", *flash_arguments, APPLICATION_IMAGE, timeout=60)
        ended = node.wait(10)
    finally:
        if node.process.poll() is None:
            node.stop()
    return ended


def check_boot(results, memory, text):
    status, replies = boot(memory)
    as_node = node_present(replies) == [1]
    waiting = bootloader_waiting(replies)
    results.check(status == 0 and (as_node or waiting),
                  f"{text}: boots {'as node 1' if as_node else 'into its waiting bootloader'}",
                  f"exit {status}, frames {[(s, hex(k)) for s, k, _ in replies]}")
    return as_node


def flash_same_part(results, folder):
    """Over the same application: every operation."""
    factory = fresh_memory(folder, "factory.memory", FACTORY_IMAGE)
    node = Node(os.path.join(folder, "count.memory"), FACTORY_IMAGE, SPEED)
    wait_for_node(node)
    console(node, "flash", APPLICATION_IMAGE)
    total = nvm_operations(node.stop()[1])
    results.check(total is not None and total > 0,
                  f"a flashing over the same application takes {total} NVM operations")
    for cut in range(1, (total or 0) + 1):
        memory = os.path.join(folder, f"factory-cut-{cut}.memory")
        shutil.copy(factory, memory)
        ended = flash_until_cut(memory, cut, [])
        results.check(ended is not None and "power cut at NVM operation" in ended[1],
                      f"factory robot: the power is cut at operation {cut} of {total}",
                      str(ended))
        check_boot(results, memory, f"factory robot cut at {cut}")


def flash_new_part(results, folder):
    """Into a robot holding the bootloader only: a spread of K."""
    bare = fresh_memory(folder, "bare.memory", BOOTLOADER_IMAGE)
    counted = os.path.join(folder, "bare-count.memory")
    shutil.copy(bare, counted)
    node = Node(counted, None, SPEED)
    time.sleep(0.5)
    _, output = console(node, "flash", "--node", "1", APPLICATION_IMAGE, timeout=60)
    total = nvm_operations(node.stop()[1]) or 0
    # The bootloader erases a row and then writes it: two operations for
    # each page the console says it sends.
    pages = re.search(r"\((\d+) pages of", output)
    results.check(pages is not None and total == 2 * int(pages.group(1)),
                  f"a whole flashing takes {total} NVM operations (two a page)", output)
    cuts = sorted({1, total // 3, 2 * total // 3, total - 1, total})
    reflashed = False
    for cut in cuts:
        memory = os.path.join(folder, f"bare-cut-{cut}.memory")
        shutil.copy(bare, memory)
        ended = flash_until_cut(memory, cut, ["--node", "1"])
        results.check(ended is not None and "power cut at NVM operation" in ended[1],
                      f"bootloader-only robot: the power is cut at operation {cut} of {total}",
                      str(ended))
        as_node = check_boot(results, memory, f"bootloader-only robot cut at {cut}")
        if not as_node and not reflashed and cut >= total // 3:
            reflashed = True
            node = Node(memory, None, SPEED)
            try:
                time.sleep(0.5)
                status, output = console(node, "flash", "--node", "1", APPLICATION_IMAGE,
                                         timeout=60)
                results.check(status == 0 and wait_for_node(node) is not None,
                              f"after the cut at {cut} a new flashing succeeds and the robot "
                              f"answers as a node", output)
            finally:
                node.stop()


def store(node, folder, source):
    program = os.path.join(folder, "program.aseba")
    with open(program, "w") as text:
        text.write(source)
    wait_for_node(node, home=folder)
    console(node, "load", program, home=folder)
    console(node, "save", home=folder)
    time.sleep(0.3)  # the robot does not confirm: give the store its rows


def stored_value(memory, folder):
    node = Node(memory, None, FAST)
    try:
        wait_for_node(node, home=folder)
        _, output = console(node, "vars", "leftSpeed", home=folder)
    finally:
        node.stop()
    return output


def store_part(results, folder, parity):
    old = os.path.join(folder, "old.memory")
    node = Node(old, FACTORY_IMAGE, FAST)
    store(node, folder, OLD_PROGRAM)
    node.stop()
    counted = os.path.join(folder, "count.memory")
    shutil.copy(old, counted)
    node = Node(counted, None, FAST)
    store(node, folder, NEW_PROGRAM)
    total = nvm_operations(node.stop()[1]) or 0
    results.check(total > 0, f"storing a program over another takes {total} NVM operations")
    results.check("222" in stored_value(counted, folder), "uncut, the new program is stored")
    # Every other operation (the odd ones, or the even ones): each half of
    # the store's operations stays within a minute.
    for cut in range(1 if parity else 2, total + 1, 2):
        memory = os.path.join(folder, f"store-cut-{cut}.memory")
        shutil.copy(old, memory)
        node = Node(memory, None, FAST + ["--power-cut-at", str(cut)])
        try:
            store(node, folder, NEW_PROGRAM)
            ended = node.wait(10)
        finally:
            if node.process.poll() is None:
                node.stop()
        results.check(ended is not None and "power cut at NVM operation" in ended[1],
                      f"the power is cut at operation {cut} of {total} of the store", str(ended))
        output = stored_value(memory, folder)
        results.check("111" in output or "222" in output,
                      f"cut at {cut}: the robot boots and runs the old or the new program", output)


def main():
    parts = {"flash-same": flash_same_part, "flash-new": flash_new_part,
             "store-odd": lambda results, folder: store_part(results, folder, 1),
             "store-even": lambda results, folder: store_part(results, folder, 0)}
    part = parts.get(sys.argv[1] if len(sys.argv) > 1 else "")
    if part is None:
        print("usage: power_cut_test.py flash-same|flash-new|store-odd|store-even",
              file=sys.stderr)
        return 2
    results = Results()
    with tempfile.TemporaryDirectory() as folder:
        part(results, folder)
    return results.finish()


if __name__ == "__main__":
    sys.exit(main())
