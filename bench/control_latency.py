#!/usr/bin/env python3
"""Control API latency while clients poll devices (issue 11's closing figure).

Starts rigsimd on the default rig with the control API, then runs CLIENTS processes (default
10), each on its own keep-alive HTTP connection, polling in a loop for SECONDS each:

  1. baseline: GET /api/clock (the smallest route: the daemon's HTTP path and nothing else);
  2. measured: GET /api/devices/<name>, the clients spread over every device of the rig.

and prints median and p99 latency of each, and their ratio. Both phases run in the same
daemon, one after the other, so that the machine's noise hits both alike. Standard library
only. Usage: bench/control_latency.py [--rigsimd PATH] [--clients N] [--seconds S]
"""
import argparse
import http.client
import json
import multiprocessing
import os
import statistics
import subprocess
import sys
import tempfile
import time


def poll(args):
    host, port, paths, seconds = args
    conn = http.client.HTTPConnection(host, port, timeout=10)
    out = []
    deadline = time.monotonic() + seconds
    i = 0
    while time.monotonic() < deadline:
        path = paths[i % len(paths)]
        i += 1
        t0 = time.perf_counter()
        conn.request("GET", path)
        r = conn.getresponse()
        body = r.read()
        out.append(time.perf_counter() - t0)
        if r.status != 200:
            raise RuntimeError(f"{path}: {r.status} {body!r}")
    conn.close()
    return out


def phase(pool, host, port, clients, path_sets, seconds):
    work = [(host, port, path_sets[i % len(path_sets)], seconds) for i in range(clients)]
    lat = [x for part in pool.map(poll, work) for x in part]
    lat.sort()
    return {
        "requests": len(lat),
        "per_s": len(lat) / seconds,
        "median_us": statistics.median(lat) * 1e6,
        "p99_us": lat[int(len(lat) * 0.99)] * 1e6,
    }


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rigsimd", default=os.path.join(here, "..", "build", "release", "rigsimd"))
    ap.add_argument("--clients", type=int, default=10)
    ap.add_argument("--seconds", type=float, default=5.0)
    ap.add_argument("--rounds", type=int, default=2)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        ep = os.path.join(tmp, "ep.json")
        d = subprocess.Popen([a.rigsimd, "--ephemeral-ports", "--pty-dir", tmp, "--endpoints-json", ep,
                              "--control", "127.0.0.1:0", "--log-level", "warn"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            for _ in range(500):
                if os.path.exists(ep):
                    break
                time.sleep(0.01)
            doc = json.load(open(ep))
            host, port = doc["control"][len("http://"):].rsplit(":", 1)
            names = [dev["name"] for dev in doc["devices"]]
            with multiprocessing.Pool(a.clients) as pool:
                for r in range(a.rounds):
                    base = phase(pool, host, int(port), a.clients, [["/api/clock"]], a.seconds)
                    dev = phase(pool, host, int(port), a.clients, [[f"/api/devices/{n}" for n in names]], a.seconds)
                    print(json.dumps({"round": r + 1, "clients": a.clients, "devices": len(names),
                                      "baseline_get_clock": base, "get_device": dev,
                                      "median_ratio": dev["median_us"] / base["median_us"],
                                      "p99_ratio": dev["p99_us"] / base["p99_us"]}))
        finally:
            d.terminate()
            d.wait(10)
    return 0


if __name__ == "__main__":
    sys.exit(main())
