#!/usr/bin/env python3
"""rigsim-tap's added latency per message (issue 30's closing figure), against a direct connection
measured side by side in the same run.

Starts rigsimd on config/examples/mcs2.json and rigsim-tap between a TCP client and the MCS2
(recording to a file in a temporary directory). One client measures round trips of `:CHAN0:POS?`
(one in flight), ROUNDS times alternating N round trips straight to the daemon and N through the
tap, and prints the median and p99 of each, their ratio and the median added latency in µs, and
the recording's size. Standard library only.
Usage: bench/tap_latency.py [--build DIR] [--n N] [--rounds R]
"""
import argparse
import json
import os
import socket
import statistics
import subprocess
import tempfile
import time


def round_trips(address, n):
    out = []
    with socket.create_connection(address, timeout=10) as s, s.makefile("rb") as answers:
        s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        for _ in range(n):
            t0 = time.perf_counter()
            s.sendall(b":CHAN0:POS?\r\n")
            answers.readline()
            out.append(time.perf_counter() - t0)
    return out


def p99(xs):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, int(len(xs) * 0.99))]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(here, "..", "build", "release"))
    ap.add_argument("--n", type=int, default=2000)
    ap.add_argument("--rounds", type=int, default=5)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        ep = os.path.join(tmp, "endpoints.json")
        d = subprocess.Popen([os.path.join(a.build, "rigsimd"), "--config", os.path.join(here, "..", "config", "examples",
                              "mcs2.json"), "--ephemeral-ports", "--pty-dir", tmp, "--endpoints-json", ep,
                              "--log-level", "warn"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        tap = None
        try:
            for _ in range(200):
                if os.path.exists(ep):
                    break
                time.sleep(0.05)
            host, port = json.load(open(ep))["devices"][0]["tcp"].rsplit(":", 1)
            record = os.path.join(tmp, "session.jsonl")
            tap = subprocess.Popen([os.path.join(a.build, "rigsim-tap"), "--protocol", "mcs2", "--listen",
                                    "tcp:127.0.0.1:0", "--to", "tcp:%s:%s" % (host, port), "--record", record],
                                   stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
            tap_port = int(tap.stdout.readline().rsplit(":", 1)[1])
            direct, tapped = [], []
            for _ in range(a.rounds):
                direct += round_trips((host, int(port)), a.n)
                tapped += round_trips(("127.0.0.1", tap_port), a.n)
            md, mt = statistics.median(direct), statistics.median(tapped)
            print("round trips: %d direct, %d through the tap (%d rounds of %d, alternating)"
                  % (len(direct), len(tapped), a.rounds, a.n))
            print("direct:  median %.1f us, p99 %.1f us" % (md * 1e6, p99(direct) * 1e6))
            print("tapped:  median %.1f us, p99 %.1f us" % (mt * 1e6, p99(tapped) * 1e6))
            print("ratio:   median %.2fx, p99 %.2fx; added %.1f us per round trip (median)"
                  % (mt / md, p99(tapped) / p99(direct), (mt - md) * 1e6))
            tap.terminate()
            tap.wait(timeout=10)
            print("recording: %d lines, %d bytes" % (sum(1 for _ in open(record)), os.path.getsize(record)))
        finally:
            if tap and tap.poll() is None:
                tap.kill()
            d.terminate()
            d.wait(timeout=10)


if __name__ == "__main__":
    main()
