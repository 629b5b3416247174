#!/usr/bin/env python3
"""Every file that the user's documentation and the programs' help texts
name exists in the repository: each `NAME.md` (or a path ending in .md) in
README.md, docs/, the folders' READMEs and the string literals of tools/,
found relative to the repository's root, to the naming file's folder, or
to docs/. References to material outside the repository (../ paths) count
as missing, but for the dsPIC toolchain's documented place beside the
checkout. Tests' own READMEs, written for developers, are not scanned.

Run from the repository's root; ends with "N passed, N failed".
"""

import os
import re
import subprocess
import sys

ALLOWED_OUTSIDE = ("../shared/toolchains/",)
REFERENCE = re.compile(r"(?<![\w/.-])((?:\.\./)*[\w./-]*\w\.md)\b")


def scanned_files():
    """The documents and the tools' sources: as git lists them in a clone,
    else (a copy without .git, a release's tarball) as they are on disk."""
    listed = subprocess.run(["git", "ls-files", "*.md", "tools/*.cpp", "tools/*.hpp"],
                            capture_output=True, text=True)
    if listed.returncode == 0:
        paths = listed.stdout.split()
    else:
        paths = []
        for folder, subfolders, names in os.walk("."):
            subfolders[:] = [name for name in subfolders
                             if not name.startswith(".") and name not in ("build", "node_modules")]
            for name in names:
                path = os.path.relpath(os.path.join(folder, name))
                if name.endswith(".md") or (path.startswith("tools/") and
                                            name.endswith((".cpp", ".hpp"))):
                    paths.append(path)
    return sorted(path for path in paths
                  if not path.startswith("tests/") and "node_modules" not in path)


def text_of(path):
    with open(path, encoding="utf-8") as file:
        text = file.read()
    if path.endswith((".cpp", ".hpp")):
        # What a user reads: the string literals, raw and plain.
        literals = re.findall(r'R"\((.*?)\)"', text, re.S)
        literals += re.findall(r'"((?:[^"\\\n]|\\.)*)"', text)
        text = "\n".join(literals)
    return text


def missing_references(path):
    missing = []
    for match in REFERENCE.finditer(text_of(path)):
        reference = match.group(1)
        if reference.startswith(ALLOWED_OUTSIDE):
            continue
        candidates = [reference, os.path.join(os.path.dirname(path), reference),
                      os.path.join("docs", reference)]
        if reference.startswith("../") or not any(os.path.isfile(c) for c in candidates):
            missing.append(reference)
    return missing


def main():
    passed = failed = 0
    for path in scanned_files():
        missing = missing_references(path)
        if missing:
            failed += 1
            print(f"FAIL {path}: names {', '.join(sorted(set(missing)))}, not in the repository")
        else:
            passed += 1
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
