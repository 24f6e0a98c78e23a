#!/usr/bin/env python3
"""How many acknowledged EEPROM saves kill -9 loses, with and without --state-sync.

Usage: bench/state_durability.py RIGSIMD [TRIALS] [SAVES]

Each trial starts RIGSIMD on the built-in default rig with --state-file, then on its TDC001
sends SAVES pairs of MOT_SET_VELPARAMS (maximum velocity = 1000 * i) and
MOT_SET_EEPROMPARAMS(VELPARAMS), then MOT_REQ_VELPARAMS; once the GET answer is read (every
save before it was acknowledged as far as APT acknowledges: the unit has acted on it), the
daemon is killed with SIGKILL. The state file then holds the velocity of the last save that
reached the disk: SAVES - i are lost. Prints per mode the losses of each trial and the range.
Not a test (it depends on the disk): bench/README.md records its figures.
"""
import json
import os
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time


def frame(msg_id, data=b"", p1=0, p2=0, dest=0x50, src=0x01):
    if data:
        return struct.pack("<HHBB", msg_id, len(data), dest | 0x80, src) + data
    return struct.pack("<HBBBB", msg_id, p1, p2, dest, src)


def read_frame(sock, buf):
    while True:
        if len(buf) >= 6:
            msg_id, length = struct.unpack_from("<HH", buf)
            has_data = buf[4] & 0x80
            total = 6 + (length if has_data else 0)
            if len(buf) >= total:
                return msg_id, bytes(buf[6:total]), buf[total:]
        chunk = sock.recv(4096)
        if not chunk:
            raise EOFError("daemon closed the connection")
        buf += chunk


def trial(rigsimd, saves, sync):
    with tempfile.TemporaryDirectory() as tmp:
        state = os.path.join(tmp, "state.json")
        endpoints = os.path.join(tmp, "endpoints.json")
        args = [rigsimd, "--state-file", state, "--ephemeral-ports", "--pty-dir", os.path.join(tmp, "ptys"),
                "--endpoints-json", endpoints, "--log-level", "error"]
        if sync:
            args.append("--state-sync")
        proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            for _ in range(500):
                if os.path.exists(endpoints):
                    break
                time.sleep(0.01)
            ep = json.load(open(endpoints))
            tcp = next(d["tcp"] for d in ep["devices"] if d["name"] == "tdc001")
            host, port = tcp.rsplit(":", 1)
            sock = socket.create_connection((host, int(port)))
            out = bytearray()
            for i in range(1, saves + 1):
                out += frame(0x0413, struct.pack("<HIII", 1, 0, 4506, 1000 * i))
                out += frame(0x04B9, struct.pack("<HH", 1, 0x0413))
            out += frame(0x0414, p1=1)
            sock.sendall(out)
            buf = bytearray()
            while True:
                msg_id, data, buf = read_frame(sock, buf)
                if msg_id == 0x0415:
                    break
            last = struct.unpack_from("<HIII", data)[3]
            assert last == 1000 * saves, f"the unit holds {last}, expected {1000 * saves}"
            proc.send_signal(signal.SIGKILL)
            proc.wait()
            try:
                saved = json.load(open(state))["tdc001"]["bay0/0x0413"]
                kept = struct.unpack_from("<HIII", bytes.fromhex(saved))[3] // 1000
            except (FileNotFoundError, KeyError):
                kept = 0
            return saves - kept
        finally:
            if proc.poll() is None:
                proc.kill()
                proc.wait()


def main():
    rigsimd = sys.argv[1]
    trials = int(sys.argv[2]) if len(sys.argv) > 2 else 13
    saves = int(sys.argv[3]) if len(sys.argv) > 3 else 200
    for sync in (False, True):
        lost = [trial(rigsimd, saves, sync) for _ in range(trials)]
        name = "--state-sync" if sync else "written behind"
        print(f"{name:15s} {saves} saves, kill -9 after the last was acted on: lost {lost} (min {min(lost)}, max {max(lost)})")


if __name__ == "__main__":
    main()
