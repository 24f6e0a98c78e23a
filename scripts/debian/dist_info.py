#!/usr/bin/env python3
"""Write the rigsim package's .dist-info directory (METADATA, entry_points.txt, INSTALLER) into
OUT, from python/pyproject.toml through the in-tree build backend, so that an installed copy of
python/rigsim is a distribution Python sees: `pytest` finds the rigsim plugin by its pytest11
entry point, `importlib.metadata.version("rigsim")` answers. No RECORD: dpkg, not pip, owns the
files (Debian's own Python packages ship theirs the same way).

  scripts/debian/dist_info.py OUT"""

import os
import shutil
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "python", "_backend"))
import rigsim_build  # noqa: E402  (after the path above)


def main(out):
    project = rigsim_build._project()
    files = dict(rigsim_build._dist_info_files(project))
    info = rigsim_build._dist_info(project)
    files.pop(f"{info}/WHEEL", None)
    files[f"{info}/INSTALLER"] = b"dpkg\n"
    # Only this version's: a directory left by an earlier version would be installed beside it.
    if os.path.isdir(out):
        for name in os.listdir(out):
            if name.endswith(".dist-info") and name != info:
                shutil.rmtree(os.path.join(out, name))
    for path, data in files.items():
        target = os.path.join(out, path)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        old = open(target, "rb").read() if os.path.exists(target) else None
        if old != data:
            with open(target, "wb") as f:
                f.write(data)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
