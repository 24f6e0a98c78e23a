#!/usr/bin/env python3
"""Control API latency while clients poll devices (issue 11's closing figure).

Starts rigsimd on the default rig with the control API. One measuring client sends
GET /api/devices/<name> (round robin over the rig's devices) on a keep-alive connection for
SECONDS, twice per round, side by side in the same daemon:

  1. baseline: nothing else runs;
  2. loaded: CLIENTS processes (default 10) poll the devices through their own protocols
     over TCP as fast as they can (MCS ":GS0", APT MGMSG_MOT_REQ_POSCOUNTER), one
     request in flight each, as drivers polling status do.

It prints median and p99 of the control requests' latency in both, their ratio, and the
device polls served per second. Standard library only.
Usage: bench/control_latency.py [--rigsimd PATH] [--clients N] [--seconds S] [--rounds R]
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


def device_poll(args):
    """One device client: requests as fast as answers come, for `seconds`; the count."""
    import socket
    host, port, protocol, model, seconds = args
    s = socket.create_connection((host, port), timeout=5)
    s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    if protocol == "mcs":
        req, size = b":GS0\n", len(b":S0,0\n")
    else:
        # A benchtop rack (BSC203, BBD203) answers from its bays (0x21...), a cube from 0x50.
        dest = 0x21 if model.startswith("B") else 0x50
        req, size = bytes([0x11, 0x04, 0x01, 0x00, dest, 0x01]), 12
    n = 0
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        s.sendall(req)
        got = b""
        while len(got) < size:
            chunk = s.recv(size - len(got))
            if not chunk:
                raise RuntimeError("device closed the connection")
            got += chunk
        n += 1
    s.close()
    return n


def summary(lat, seconds):
    lat = sorted(lat)
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
            paths = [f"/api/devices/{n}" for n in names]
            targets = []
            for i in range(a.clients):
                dev = doc["devices"][i % len(doc["devices"])]
                h, p = dev["tcp"].rsplit(":", 1)
                targets.append((h, int(p), dev["protocol"], dev["model"], a.seconds))
            with multiprocessing.Pool(a.clients) as pool:
                for r in range(a.rounds):
                    base = summary(poll((host, int(port), paths, a.seconds)), a.seconds)
                    load = pool.map_async(device_poll, targets)
                    loaded = summary(poll((host, int(port), paths, a.seconds)), a.seconds)
                    polls = sum(load.get())
                    print(json.dumps({"round": r + 1, "device_clients": a.clients, "devices": len(names),
                                      "baseline": base, "loaded": loaded,
                                      "device_polls_per_s": polls / a.seconds,
                                      "median_ratio": loaded["median_us"] / base["median_us"],
                                      "p99_ratio": loaded["p99_us"] / base["p99_us"]}))
        finally:
            d.terminate()
            d.wait(10)
    return 0


if __name__ == "__main__":
    sys.exit(main())
