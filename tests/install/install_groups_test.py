#!/usr/bin/env python3
"""Which groups of scripts/install-deps.sh each make target installs, read
from `make -n TARGET` in an empty build folder (what a fresh machine would
run), against the README's promises: `make run` needs the small build group
only, `make test` what the tests run, and every other target what it uses.
A target that would build something without installing its packages fails
on a fresh machine (CI's fresh system shows it); one that installs more
than it needs burdens every user: both are caught here.

Run from the repository's root; ends with "N passed, N failed".
"""

import os
import re
import subprocess
import sys
import tempfile

EXPECTED = {
    "run": {"build"},
    "all": {"build", "test", "bench", "dspic30", "cross"},
    "test": {"build", "test", "dspic30"},  # the ARM compiler of its QEMU tests is in "test"
    "bench": {"build", "test", "bench", "dspic30"},
    "experiment": {"build", "experiment"},
    "cross-check": {"build", "cross"},
    "fuzz": {"fuzz"},
    "dspic30": {"build", "dspic30"},
    "stm32f4": {"build", "cross"},
}


def groups_installed(target, build):
    environment = {k: v for k, v in os.environ.items() if k not in ("MAKEFLAGS", "MFLAGS")}
    plan = subprocess.run(["make", "-n", target, f"BUILD={build}"], capture_output=True,
                          text=True, env=environment).stdout
    return set(re.findall(r"^BUILD=\S+ scripts/install-deps.sh ([a-z0-9]+)$", plan, re.M))


def main():
    passed = failed = 0
    with tempfile.TemporaryDirectory() as build:
        for target, expected in EXPECTED.items():
            found = groups_installed(target, build)
            if found == expected:
                passed += 1
                print(f"ok   make {target}: {' '.join(sorted(found))}")
            else:
                failed += 1
                print(f"FAIL make {target} installs {sorted(found)}, expected {sorted(expected)}")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
