#!/usr/bin/env python3
"""CTest unit_repository_stands_alone: a user's clone holds nothing outside the repository, so no
file may lean on one. Fails (exit 1, naming file and line) when a file of the repository names a
path outside it (a sibling folder such as ../shared, where the developers keep the manuals) or a
machine's own path (a home or work directory): manuals are cited by title, issue and section,
and scripts take such paths as arguments.

Usage: scripts/check_standalone.py [SOURCE_DIR]. Standard library only."""

import os
import re
import subprocess
import sys

# Patterns that only a path outside the repository or of one machine can match.
FORBIDDEN = [
    (re.compile(r"\.\./shared\b|\bshared/(specs|tools|hooks)\b"), "a path outside the repository (../shared)"),
    (re.compile(r"(?<![\w.])/(home|root|work|Users)/\w"), "a machine's own path"),
]
SKIP_DIRS = {".git", "build", "__pycache__"}


def repository_files(root):
    """The files git tracks or would track (not ignored), else every file under `root` but build
    output."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others", "--exclude-standard"], capture_output=True, check=True).stdout
        return [os.path.join(root, p) for p in out.decode().split("\0") if p]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for d, dirs, names in os.walk(root):
            dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not x.startswith("build")]
            files.extend(os.path.join(d, n) for n in names)
        return files


def main(argv):
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    me = os.path.abspath(__file__)
    problems = []
    for path in repository_files(root):
        if os.path.abspath(path) == me or not os.path.isfile(path):
            continue
        try:
            with open(path, encoding="utf-8") as f:
                lines = f.readlines()
        except (UnicodeDecodeError, OSError):
            continue   # binary files
        for number, line in enumerate(lines, 1):
            for pattern, what in FORBIDDEN:
                if pattern.search(line):
                    problems.append(f"{os.path.relpath(path, root)}:{number}: {what}: {line.strip()[:120]}")
    if problems:
        sys.stderr.write("check_standalone.py: files that lean on something outside the repository:\n  "
                         + "\n  ".join(problems) + "\n")
        return 1
    print(f"check_standalone.py: no file of {root} names a path outside it")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
