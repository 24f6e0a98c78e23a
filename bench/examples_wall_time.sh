#!/bin/sh
# Wall time of the example suite (docs/examples) with run_until_idle and stepped time, and of
# the same suite in real time (RIGSIM_REAL_TIME=1), side by side: issue 11's closing figure.
# Usage: bench/examples_wall_time.sh [RIGSIMD] [ROUNDS]
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
rigsimd=${1:-$here/build/release/rigsimd}
rounds=${2:-2}
# Seconds the suite takes; "failed" appended if it failed.
run() {
  /usr/bin/python3 - "$here" "$rigsimd" <<'PY'
import os, subprocess, sys, time
here, rigsimd = sys.argv[1], sys.argv[2]
env = dict(os.environ, PYTHONPATH=os.path.join(here, "python"), PYTHONDONTWRITEBYTECODE="1")
t0 = time.monotonic()
r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "rigsim.pytest_plugin",
                    "--rigsimd", rigsimd, os.path.join(here, "docs", "examples")],
                   env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
print(f"{time.monotonic() - t0:.2f}" + ("" if r.returncode == 0 else " (failed)"))
PY
}
i=1
while [ "$i" -le "$rounds" ]; do
  fast=$(run)
  real=$(RIGSIM_REAL_TIME=1 && export RIGSIM_REAL_TIME && run)
  echo "round $i: run_until_idle $fast s, real time $real s"
  i=$((i + 1))
done
