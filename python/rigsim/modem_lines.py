"""Print the path of the RTS/DTR shim (librigsim_modemlines.so) for LD_PRELOAD:

    LD_PRELOAD=$(python3 -m rigsim.modem_lines --rigsimd build/release/rigsimd) python3 -m pytest ...

A serial client that sets RTS or DTR on rigsimd's pty (pyLabLib's Thorlabs classes, the Thorlabs
APT port set-up) needs the shim loaded in its own process, so LD_PRELOAD must name it when that
process starts (docs/python.md, "Serial clients that toggle RTS/DTR"). Exit 1 with a message on
standard error when it is not found."""

from __future__ import annotations

import argparse
import sys
from typing import Sequence

from rigsim.daemon import RigsimError, modem_lines_shim


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python3 -m rigsim.modem_lines",
        description="Print the path of librigsim_modemlines.so (the RTS/DTR shim) for LD_PRELOAD: "
                    "$RIGSIM_MODEMLINES, else beside rigsimd, else in ../lib beside it.")
    parser.add_argument("--rigsimd", metavar="PATH", default=None,
                        help="the rigsimd whose shim to find (default: $RIGSIMD, else rigsimd on PATH)")
    args = parser.parse_args(argv)
    try:
        print(modem_lines_shim(args.rigsimd))
    except RigsimError as e:
        print(f"rigsim.modem_lines: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
