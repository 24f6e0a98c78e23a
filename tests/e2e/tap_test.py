"""rigsim-tap between a client and a unit, with a rigsimd playing the real unit (docs/conformance.md):
the bytes pass unchanged both ways, and the recording holds them byte for byte as the daemon's own
wire log saw them, each frame decoded, whether the unit is an MCS2 on TCP or an APT unit on a serial
line (the daemon's pty) and the client on a pty. Run by CTest (e2e_tap) with RIGSIM_TAP set."""

import json
import os
import socket
import struct
import subprocess
import time

import pytest

TAP = os.environ.get("RIGSIM_TAP", "")
SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")

pytestmark = pytest.mark.skipif(not TAP, reason="RIGSIM_TAP names the rigsim-tap binary (CTest sets it)")


def start_tap(tmp_path, protocol, listen, to):
    record = tmp_path / "session.jsonl"
    tap = subprocess.Popen([TAP, "--protocol", protocol, "--listen", listen, "--to", to, "--record", str(record)],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    first = tap.stdout.readline()   # "rigsim-tap: listening on ..."
    assert first.startswith("rigsim-tap: listening on"), first + tap.stderr.read()
    return tap, record, first


def stop_tap(tap):
    tap.terminate()
    assert tap.wait(timeout=10) == 0


def recording(path):
    lines = [json.loads(line) for line in path.read_text().splitlines()]
    assert lines[0]["rigsim_recording"] == 1
    return lines[0], lines[1:]


def wire_bytes(log, direction):
    return b"".join(bytes.fromhex(e["hex"]) for e in log["entries"] if e["direction"] == direction)


def recorded_bytes(records, direction):
    return b"".join(bytes.fromhex(r["bytes"]) for r in records if r.get("dir") == direction)


def test_mcs2_over_tcp_is_recorded_as_the_unit_saw_it(rigsim, tmp_path):
    rig = rigsim(os.path.join(SOURCE, "config", "examples", "mcs2.json"))
    host, port = rig.endpoint("mcs2").address
    tap, record, first = start_tap(tmp_path, "mcs2", "tcp:127.0.0.1:0", "tcp:%s:%d" % (host, port))
    tap_port = int(first.rsplit(":", 1)[1])
    with socket.create_connection(("127.0.0.1", tap_port), timeout=5) as s, s.makefile("rb") as answers:
        s.sendall(b"*IDN?\r\n")
        assert answers.readline() == b"SmarAct GmbH,MCS2,MCS2-00001234,current\r\n"
        s.sendall(b":CHAN0:MMOD 0;VEL 1000000000\r\n:MOVE0 1000\r\n:CHAN0:NOPE?\r\n:SYST:ERR?\r\n")
        assert answers.readline() == b'-113,"Undefined header"\r\n'
        s.sendall(b":CHAN0:POS:TARG?;:DEV:SNUM?\r\n")   # sent in pieces a frame does not care about
        assert answers.readline() == b'1000; "MCS2-00001234"\r\n'
    time.sleep(0.3)
    stop_tap(tap)
    header, records = recording(record)
    assert header["protocol"] == "mcs2" and header["to"].startswith("tcp:")
    log = rig.log("mcs2")
    assert recorded_bytes(records, "in") == wire_bytes(log, "in")
    assert recorded_bytes(records, "out") == wire_bytes(log, "out")
    frames = [r for r in records if "decoded" in r]
    assert [r["decoded"]["text"] for r in frames if r["dir"] == "in"][:3] == [
        "*IDN?", ":CHAN0:MMOD 0;VEL 1000000000", ":MOVE0 1000"]
    assert [r["event"] for r in records if "event" in r] == ["connect", "unit", "disconnect", "stop"]
    assert all(r["t_us"] >= 0 for r in records)
    assert [r["seq"] for r in records] == list(range(len(records)))


def test_apt_on_a_serial_line_through_a_pty_client(rigsim, tmp_path):
    rig = rigsim()
    unit_pty = rig.endpoint("kdc101").pty
    client_link = str(tmp_path / "tap-kdc101")
    tap, record, _ = start_tap(tmp_path, "apt", "pty:" + client_link, "serial:%s,115200" % unit_pty)
    fd = os.open(client_link, os.O_RDWR | os.O_NOCTTY)
    try:
        import termios, tty   # noqa: E401
        tty.setraw(fd)
        os.write(fd, struct.pack("<HBBBB", 0x0005, 0, 0, 0x50, 0x01))   # HW_REQ_INFO
        data = b""
        deadline = time.time() + 5
        while len(data) < 90 and time.time() < deadline:
            data += os.read(fd, 90 - len(data))
        assert len(data) == 90 and struct.unpack_from("<H", data)[0] == 0x0006   # HW_GET_INFO
        attrs = termios.tcgetattr(fd)                # the client changes the line's rate: the tap
        attrs[4] = attrs[5] = termios.B9600          # sets the unit's port to it before its next bytes
        termios.tcsetattr(fd, termios.TCSANOW, attrs)
        os.write(fd, b"\x11\x04\x00")   # half a header: cut when the tap stops
        time.sleep(0.3)
    finally:
        os.close(fd)
    stop_tap(tap)
    _, records = recording(record)
    frames = [r for r in records if "decoded" in r]
    assert frames[0]["dir"] == "in" and frames[0]["decoded"]["name"] == "MGMSG_HW_REQ_INFO"
    assert frames[1]["dir"] == "out" and frames[1]["decoded"]["name"] == "MGMSG_HW_GET_INFO"
    assert bytes.fromhex(frames[1]["bytes"]) == data
    bauds = [r for r in records if r.get("event") == "baud"]
    assert [b["baud"] for b in bauds] == [9600]
    assert bauds[0]["seq"] < [r for r in records if r.get("partial")][0]["seq"]
    partial = [r for r in records if r.get("partial")]
    assert len(partial) == 1 and partial[0]["bytes"] == "110400"   # no byte lost
    assert not os.path.exists(client_link)   # the tap removes its link


def test_bad_arguments_exit_2_naming_the_flag(tmp_path):
    run = subprocess.run([TAP, "--protocol", "can", "--listen", "tcp:127.0.0.1:0", "--to", "tcp:127.0.0.1:1",
                          "--record", str(tmp_path / "r")], capture_output=True, text=True, timeout=10)
    assert run.returncode == 2 and run.stderr.startswith("rigsim-tap: --protocol: expected apt, mcs or mcs2")
    run = subprocess.run([TAP, "--protocol", "apt", "--listen", "tcp:127.0.0.1:0", "--to", "tcp:127.0.0.1:1",
                          "--record", "/nonexistent/dir/r"], capture_output=True, text=True, timeout=10)
    assert run.returncode == 2 and "/nonexistent/dir/r: cannot write the recording" in run.stderr
