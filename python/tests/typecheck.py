#!/usr/bin/python3
"""CTest python_typecheck: the rigsim package's type hints hold, checked by Debian's mypy
(python3-mypy, scripts/deps.sh --test). Exit 1 on any mypy error, and when mypy is missing.
Usage: typecheck.py [PYTHON_DIR] (default: the python/ directory this file is in)."""

import importlib.util
import os
import subprocess
import sys

# --strict: every function and method annotated, no Any leaking out as a return value, no
#   implicit re-exports, generics with their parameters: the package ships py.typed, so a user's
#   own mypy run sees these hints as the package's contract.
# --python-version 3.9: pyproject.toml's requires-python; an annotation or alias that only a newer
#   Python evaluates (`X | Y` outside an annotation) is an error, not a crash on the user's 3.9.
# --config-file= (empty): no mypy.ini, setup.cfg or ~/.config/mypy/config of this machine changes
#   the flags (mypy's documented way to ignore every config file).
# --cache-dir=/dev/null: mypy writes no .mypy_cache into the source tree (or anywhere).
FLAGS = ["--strict", "--python-version", "3.9", "--config-file=", "--cache-dir=/dev/null"]


def main():
    python_dir = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    if importlib.util.find_spec("mypy") is None:
        sys.exit(f"FAIL: mypy is not installed for {sys.executable}: run scripts/deps.sh --test "
                 "(it installs Debian's python3-mypy)")
    package = os.path.join(python_dir, "rigsim")
    cmd = [sys.executable, "-m", "mypy", *FLAGS, package]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    sys.stdout.write(result.stdout)
    sys.stderr.write(result.stderr)
    if result.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {result.returncode}")
    print(f"PASS: mypy {' '.join(FLAGS)} over {package}")


if __name__ == "__main__":
    main()
