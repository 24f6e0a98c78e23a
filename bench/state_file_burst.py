#!/usr/bin/env python3
"""Round trip of one APT device while another saves in a burst (--state-file).

Usage: bench/state_file_burst.py DAEMON [ROUND_TRIPS]   (BENCH_DIR: where the state file
goes, default /var/tmp: a disk, not a tmpfs, so that fsync costs what it costs.)

Starts DAEMON (the default rig) with --state-file in a fresh temp dir; measures
REQ_POSCOUNTER round trips on tdc001 over TCP, first alone (the baseline), then while a
second client sends SET_VELPARAMS + MOT_SET_EEPROMPARAMS pairs to kdc101 every 0.5 ms.
Prints p50/p99 of both and their ratios to the baseline of the same run (a Python client:
the absolute figures include its overhead; the ratio is the figure).
"""
import json, os, shutil, signal, socket, subprocess, sys, tempfile, threading, time

daemon = sys.argv[1]
n = int(sys.argv[2]) if len(sys.argv) > 2 else 3000
d = tempfile.mkdtemp(prefix="rigsim-bench-", dir=os.environ.get("BENCH_DIR", "/var/tmp"))
eps = os.path.join(d, "ep.json")
p = subprocess.Popen([daemon, "--ephemeral-ports", "--pty-dir", d + "/pty", "--endpoints-json", eps,
                      "--state-file", d + "/state.json", "--log-level", "error"],
                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
deadline = time.time() + 15
while not os.path.exists(eps):
    if time.time() > deadline:
        sys.exit("no endpoints")
    time.sleep(0.01)
devs = {e["name"]: e for e in json.load(open(eps))["devices"]}

def connect(name):
    host, port = devs[name]["tcp"].rsplit(":", 1)
    s = socket.create_connection((host, int(port)))
    s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return s

m = connect("tdc001")
req = bytes.fromhex("11 04 01 00 50 01")

def measure(count):
    out = []
    for _ in range(count):
        t0 = time.perf_counter()
        m.sendall(req)
        got = b""
        while len(got) < 12:
            got += m.recv(12 - len(got))
        out.append((time.perf_counter() - t0) * 1e6)
    out.sort()
    return out[len(out) // 2], out[int(len(out) * 0.99)]

measure(500)
base = measure(n)
stop = threading.Event()
saves = [0]
def burst():
    b = connect("kdc101")
    vel = bytes.fromhex("13 04 0E 00 D0 01 01 00 00 00 00 00 10 00 00 00 00 10 00 00")
    save = bytes.fromhex("B9 04 04 00 D0 01 01 00 13 04")
    while not stop.is_set():
        b.sendall(vel + save)
        saves[0] += 1
        time.sleep(0.0005)
    b.close()
t = threading.Thread(target=burst)
t.start()
time.sleep(0.2)
loaded = measure(n)
stop.set()
t.join()
p.send_signal(signal.SIGTERM)
p.wait(10)
shutil.rmtree(d, ignore_errors=True)
print(f"{daemon}")
print(f"  baseline   p50 {base[0]:8.1f} us  p99 {base[1]:8.1f} us")
print(f"  save burst p50 {loaded[0]:8.1f} us  p99 {loaded[1]:8.1f} us  ({saves[0]} saves)")
print(f"  ratio burst/baseline: p50 {loaded[0]/base[0]:.2f}  p99 {loaded[1]/base[1]:.2f}")
