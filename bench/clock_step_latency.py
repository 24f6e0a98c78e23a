#!/usr/bin/env python3
"""Device round trips while a long POST /api/clock step runs (issue 24, point 3).

Starts rigsimd, paused, on a rig of an MCS and a BPC303 whose bay plays a continuous LUT at
1 kHz (so every tick of the step costs work), and measures an MCS client's ":GS0" round trip
side by side in the same daemon:

  1. baseline: for as long as the step below took, nothing else runs;
  2. during: while one POST {"step_ms": STEP} runs (sliced on the daemon's loop).

It prints the step's wall time, the median, p99 and maximum round trip of both, and their
ratios. Before the step was sliced, the first round trip during it waited for the whole step.
Standard library only.
Usage: bench/clock_step_latency.py [--rigsimd PATH] [--step-ms MS] [--rounds R]
"""
import argparse
import http.client
import json
import os
import socket
import statistics
import struct
import subprocess
import sys
import tempfile
import threading
import time

RIG = {"tick_hz": 1000, "devices": [
    {"name": "mcs", "protocol": "mcs", "tcp_port": 0,
     "mcs": {"channels": [{"sensor_type": "S", "travel_nm": [-10500000, 10500000]}]}},
    {"name": "bpc", "protocol": "apt", "model": "BPC303", "tcp_port": 0,
     "apt": {"hardware_max_voltage_v": 150, "bays": [{"travel_um": 20, "max_voltage_v": 150}]}}]}


def to_bay(message_id, data):
    return struct.pack("<HHBB", message_id, len(data), 0xA1, 0x01) + data


def start_lut(address):
    s = socket.create_connection(address, timeout=5)
    for k in range(10):
        s.sendall(to_bay(0x0700, struct.pack("<HHh", 1, k, 1000 + 100 * k)))   # PZ_SET_OUTPUTLUT
    s.sendall(to_bay(0x0703, struct.pack("<HHHiiiiHiH", 1, 1, 10, 1, 1, 0, 0, 0, 0, 0)))   # continuous
    s.sendall(bytes([0x06, 0x07, 0x01, 0x00, 0x21, 0x01]))   # PZ_START_LUTOUTPUT
    return s


def round_trips(address, stop):
    s = socket.create_connection(address, timeout=120)
    s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    out = []
    while not stop():
        t0 = time.perf_counter()
        s.sendall(b":GS0\n")
        answer = b""
        while not answer.endswith(b"\n"):
            answer += s.recv(64)
        out.append(time.perf_counter() - t0)
    s.close()
    return out


def post(control, body):
    conn = http.client.HTTPConnection(*control, timeout=600)
    conn.request("POST", "/api/clock", json.dumps(body), {"Content-Type": "application/json"})
    answer = conn.getresponse().read()
    conn.close()
    return answer


def summary(samples):
    ms = sorted(x * 1000 for x in samples)
    return statistics.median(ms), ms[int(len(ms) * 0.99)], ms[-1], len(ms)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--rigsimd", default=os.path.join(here, "..", "build", "release", "rigsimd"))
    p.add_argument("--step-ms", type=int, default=3_600_000)
    p.add_argument("--rounds", type=int, default=3)
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as d:
        rig, endpoints = os.path.join(d, "rig.json"), os.path.join(d, "ep.json")
        with open(rig, "w") as f:
            json.dump(RIG, f)
        daemon = subprocess.Popen([args.rigsimd, "--config", rig, "--paused", "--control", "127.0.0.1:0",
                                   "--pty-dir", os.path.join(d, "pty"), "--endpoints-json", endpoints,
                                   "--log-level", "warn"], stderr=subprocess.DEVNULL)
        try:
            deadline = time.monotonic() + 10
            while not os.path.exists(endpoints):
                if time.monotonic() > deadline or daemon.poll() is not None:
                    sys.exit("rigsimd did not start")
                time.sleep(0.01)
            time.sleep(0.05)
            ep = json.load(open(endpoints))
            host, port = ep["control"][len("http://"):].rsplit(":", 1)
            control = (host, int(port))
            by_name = {x["name"]: x for x in ep["devices"]}

            def address(name):
                h, p_ = by_name[name]["tcp"].rsplit(":", 1)
                return h, int(p_)
            lut = start_lut(address("bpc"))
            for r in range(args.rounds):
                done = threading.Event()
                result = {}
                t0 = time.perf_counter()
                worker = threading.Thread(target=lambda: (post(control, {"step_ms": args.step_ms}), done.set()))
                worker.start()
                result["during"] = round_trips(address("mcs"), done.is_set)
                step_s = time.perf_counter() - t0
                worker.join()
                end = time.perf_counter() + step_s
                result["baseline"] = round_trips(address("mcs"), lambda: time.perf_counter() >= end)
                b, dur = summary(result["baseline"]), summary(result["during"])
                print(f"round {r + 1}: step {args.step_ms} ms of clock took {step_s:.2f} s of wall time")
                print(f"  baseline  median {b[0]:.3f} ms  p99 {b[1]:.3f} ms  max {b[2]:.3f} ms  ({b[3]} round trips)")
                print(f"  during    median {dur[0]:.3f} ms  p99 {dur[1]:.3f} ms  max {dur[2]:.3f} ms  ({dur[3]} round trips)")
                print(f"  ratio     median {dur[0] / b[0]:.1f}x  p99 {dur[1] / b[1]:.1f}x  max {dur[2] / b[2]:.1f}x;"
                      f" max during / step wall time {dur[2] / 1000 / step_s:.4f}")
            lut.close()
        finally:
            daemon.terminate()
            daemon.wait(10)


if __name__ == "__main__":
    main()
