#!/usr/bin/python3
"""APT over the pty with an unmodified pyserial client (Debian's python3-serial).

Thorlabs APT clients open the port as the APT manual says (115200 8N1, RTS/CTS) and then,
as thorlabs-apt-protocol's README and many drivers do:

    port = serial.Serial(path, 115200, rtscts=True, timeout=...)
    port.rts = True; port.reset_input_buffer(); port.reset_output_buffer(); port.rts = False

A Linux pty has no modem lines, so `port.rts = True` fails with ENOTTY on rigsimd's pty
unless the client runs with LD_PRELOAD=librigsim_modemlines.so (docs/cli.md). Cases:

  shim  the client set-up above, DTR toggles and CTS/DSR/CD reads under the shim, then
        HW_NO_FLASH_PROGRAMMING, HW_REQ_INFO and MOT_REQ_POSCOUNTER to the default rig's
        TDC001;
  bare  without the shim: purge, break and baud-rate changes keep the link working, and
        assigning `port.rts` raises OSError(ENOTTY), the reason the shim exists.

Usage (CTest runs it): apt_pyserial_test.py --case shim|bare --rigsimd PATH --shim PATH.
The script starts rigsimd itself and runs the client in a child process (LD_PRELOAD has to
be set when a process starts). Standard library and pyserial only; every wait polls with a
deadline; the daemon gets SIGTERM at the end, whatever happened.
"""

import argparse
import errno
import fcntl
import json
import os
import signal
import struct
import subprocess
import sys
import tempfile
import termios
import time

PYTHON = "/usr/bin/python3"
DEVICE = "tdc001"
START_TIMEOUT_S = 15.0
ANSWER_TIMEOUT_S = 3.0
CLIENT_TIMEOUT_S = 30.0
SHUTDOWN_TIMEOUT_S = 5.0

# APT frames (APT manual, "Generic system control messages" and MGMSG_MOT_REQ_POSCOUNTER),
# host (0x01) to the controller (0x50).
HW_NO_FLASH_PROGRAMMING = bytes.fromhex("180000005001")
HW_REQ_INFO = bytes.fromhex("050000005001")
HW_GET_INFO_HEADER = bytes.fromhex("060054008150")
HW_GET_INFO_LEN = 6 + 84
MOT_REQ_POSCOUNTER = bytes.fromhex("110401005001")
MOT_GET_POSCOUNTER_START = bytes.fromhex("1204060081500100")
MOT_GET_POSCOUNTER_LEN = 6 + 6

# Modem-line bits of TIOCMGET (linux/termios.h via the termios module).
TIOCM_DTR = termios.TIOCM_DTR
TIOCM_RTS = termios.TIOCM_RTS
TIOCM_CTS = termios.TIOCM_CTS
TIOCM_CD = termios.TIOCM_CD
TIOCM_DSR = termios.TIOCM_DSR
TIOCM_RI = termios.TIOCM_RI


class TestFailure(Exception):
    """A check failed; the message says what was expected and what came."""


def check(condition, message):
    if not condition:
        raise TestFailure(message)


def import_serial():
    """pyserial, or a failure naming the Debian package (a missing module must not skip)."""
    try:
        import serial
    except ImportError as e:
        raise TestFailure(
            f"{sys.executable} cannot import the serial module ({e}): install the Debian "
            "package python3-serial (scripts/deps.sh does)") from e
    return serial


# --- the client (child process) ---------------------------------------------------------

def read_exactly(port, n, what):
    """Exactly n bytes within the answer timeout (pyserial's read polls; no fixed sleep)."""
    deadline = time.monotonic() + ANSWER_TIMEOUT_S
    data = b""
    while len(data) < n and time.monotonic() < deadline:
        data += port.read(n - len(data))
    check(len(data) == n,
          f"{what}: expected {n} bytes within {ANSWER_TIMEOUT_S} s, got {len(data)}: {data.hex(' ')}")
    return data


def request_info(port, context):
    """HW_REQ_INFO -> the 90-byte HW_GET_INFO of a TDC001."""
    port.write(HW_REQ_INFO)
    info = read_exactly(port, HW_GET_INFO_LEN, f"HW_GET_INFO {context}")
    check(info[:6] == HW_GET_INFO_HEADER,
          f"HW_GET_INFO {context}: header {info[:6].hex(' ')}, expected {HW_GET_INFO_HEADER.hex(' ')}")
    check(info[6 + 4:6 + 10] == b"TDC001",
          f"HW_GET_INFO {context}: model {info[6 + 4:6 + 12]!r}, expected b'TDC001'")
    return info


def request_position(port):
    """MOT_REQ_POSCOUNTER (channel 1) -> 12 bytes of MOT_GET_POSCOUNTER."""
    port.write(MOT_REQ_POSCOUNTER)
    answer = read_exactly(port, MOT_GET_POSCOUNTER_LEN, "MOT_GET_POSCOUNTER")
    check(answer[:8] == MOT_GET_POSCOUNTER_START,
          f"MOT_GET_POSCOUNTER: {answer.hex(' ')}, expected it to start "
          f"{MOT_GET_POSCOUNTER_START.hex(' ')}")


def modem_lines(port):
    """The TIOCMGET word of the port, read directly (pyserial caches what it set)."""
    return struct.unpack("I", fcntl.ioctl(port.fd, termios.TIOCMGET, struct.pack("I", 0)))[0]


def check_lines(port, rts, dtr, context):
    lines = modem_lines(port)
    expected = ((TIOCM_RTS if rts else 0) | (TIOCM_DTR if dtr else 0)
                | TIOCM_CTS | TIOCM_DSR | TIOCM_CD)
    mask = TIOCM_RTS | TIOCM_DTR | TIOCM_CTS | TIOCM_DSR | TIOCM_CD | TIOCM_RI
    check(lines & mask == expected,
          f"TIOCMGET {context}: {lines:#x}, expected {expected:#x} "
          f"(RTS {rts}, DTR {dtr}, CTS/DSR/CD asserted, RI not)")


def client_shim(serial, path, shim):
    maps = open("/proc/self/maps", encoding="utf-8", errors="replace").read()
    check(os.path.basename(shim) in maps,
          f"the shim {shim} is not loaded in the client (LD_PRELOAD={os.environ.get('LD_PRELOAD')!r})")

    port = serial.Serial(path, 115200, rtscts=True, timeout=0.5)
    try:
        # RTS as after open (pyserial leaves it alone with rtscts), DTR raised by pyserial.
        check_lines(port, rts=True, dtr=True, context="after open")
        # The Thorlabs set-up sequence, exactly as clients write it.
        port.rts = True
        port.reset_input_buffer()
        port.reset_output_buffer()
        port.rts = False
        check_lines(port, rts=False, dtr=True, context="after the set-up sequence")
        port.dtr = False
        check_lines(port, rts=False, dtr=False, context="after dtr = False")
        port.dtr = True
        check_lines(port, rts=False, dtr=True, context="after dtr = True")
        check(port.cts is True, f"cts is {port.cts!r}, expected True")
        check(port.dsr is True, f"dsr is {port.dsr!r}, expected True")
        check(port.cd is True, f"cd is {port.cd!r}, expected True")
        check(port.ri is False, f"ri is {port.ri!r}, expected False")

        # The first answer must be HW_GET_INFO's header: HW_NO_FLASH_PROGRAMMING has none.
        port.write(HW_NO_FLASH_PROGRAMMING)
        request_info(port, "after HW_NO_FLASH_PROGRAMMING")
        request_position(port)
    finally:
        port.close()

    # A reopened port starts with RTS and DTR asserted again, as on a real port.
    port = serial.Serial(path, 115200, rtscts=True, timeout=0.5)
    try:
        check_lines(port, rts=True, dtr=True, context="after close and reopen")
        request_info(port, "after reopening")
    finally:
        port.close()

    # Anything but a pty slave keeps the kernel's answer.
    with open("/dev/null", "rb") as null:
        try:
            fcntl.ioctl(null.fileno(), termios.TIOCMGET, struct.pack("I", 0))
            raise TestFailure("TIOCMGET on /dev/null succeeded under the shim: it must pass through")
        except OSError as e:
            check(e.errno == errno.ENOTTY, f"TIOCMGET on /dev/null: {e}, expected ENOTTY")


def client_bare(serial, path):
    port = serial.Serial(path, 115200, rtscts=True, timeout=0.5)
    try:
        request_info(port, "after open")

        # Purge: an answer left unread is gone after reset_input_buffer.
        port.write(HW_REQ_INFO)
        deadline = time.monotonic() + ANSWER_TIMEOUT_S
        while port.in_waiting < HW_GET_INFO_LEN and time.monotonic() < deadline:
            time.sleep(0.002)  # poll until the unread answer has arrived
        check(port.in_waiting == HW_GET_INFO_LEN,
              f"{port.in_waiting} bytes waiting, expected the {HW_GET_INFO_LEN} of HW_GET_INFO")
        port.reset_input_buffer()
        port.reset_output_buffer()
        check(port.in_waiting == 0, f"{port.in_waiting} bytes waiting after reset_input_buffer")
        request_info(port, "after reset_input_buffer/reset_output_buffer")

        port.send_break(duration=0.25)  # tcsendbreak: a no-op on a pty
        request_info(port, "after send_break")

        for baud in (9600, 921600, 115200):
            port.baudrate = baud
            request_info(port, f"at {baud} baud")

        # Why librigsim_modemlines.so exists (docs/architecture.md). If this ever succeeds,
        # the kernel has given ptys modem lines: say so, so docs and shim get revisited.
        try:
            port.rts = True
        except OSError as e:
            check(e.errno == errno.ENOTTY,
                  f"port.rts = True without the shim: {e!r}, expected OSError(ENOTTY)")
        else:
            raise TestFailure(
                "port.rts = True succeeded on a bare pty: this kernel implements modem-line "
                "ioctls on ptys, so docs/architecture.md and docs/cli.md (which say they fail "
                "with ENOTTY) and this test need updating; librigsim_modemlines.so may no "
                "longer be needed")
        request_info(port, "after the failed port.rts")
    finally:
        port.close()


def run_client(case, path, shim):
    serial = import_serial()
    if case == "shim":
        client_shim(serial, path, shim)
    else:
        client_bare(serial, path)


# --- the daemon and the test (parent process) -------------------------------------------

def wait_for_endpoints(daemon, endpoints_path):
    deadline = time.monotonic() + START_TIMEOUT_S
    while not os.path.exists(endpoints_path):
        check(daemon.poll() is None, f"rigsimd exited with {daemon.returncode} before writing "
              f"{endpoints_path}")
        check(time.monotonic() < deadline,
              f"rigsimd did not write {endpoints_path} within {START_TIMEOUT_S} s")
        time.sleep(0.002)  # poll: re-check until the deadline
    with open(endpoints_path, encoding="utf-8") as f:
        devices = json.load(f)["devices"]
    for device in devices:
        if device["name"] == DEVICE:
            return device["pty"]
    raise TestFailure(f"no device {DEVICE!r} in {endpoints_path}: {devices}")


def stop_daemon(daemon):
    """SIGTERM, then SIGKILL after the shutdown timeout; returns the exit status."""
    if daemon.poll() is None:
        daemon.send_signal(signal.SIGTERM)
    try:
        return daemon.wait(timeout=SHUTDOWN_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        daemon.kill()
        daemon.wait()
        return None


def run_test(case, rigsimd, shim):
    import_serial()  # fail early, and clearly, if python3-serial is missing
    check(os.access(rigsimd, os.X_OK), f"no rigsimd at {rigsimd}")
    check(os.path.isfile(shim), f"no shim at {shim}")
    with tempfile.TemporaryDirectory(prefix="rigsim-e2e-pyserial-") as tmp:
        endpoints_path = os.path.join(tmp, "endpoints.json")
        log_path = os.path.join(tmp, "rigsimd.log")
        daemon_env = dict(os.environ)
        daemon_env.pop("LD_PRELOAD", None)
        with open(log_path, "wb") as log:
            daemon = subprocess.Popen(
                [rigsimd, "--ephemeral-ports", "--pty-dir", tmp,
                 "--endpoints-json", endpoints_path],
                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=log,
                env=daemon_env)
        try:
            pty_path = wait_for_endpoints(daemon, endpoints_path)
            client_env = dict(daemon_env)
            if case == "shim":
                client_env["LD_PRELOAD"] = shim
            client = subprocess.run(
                [PYTHON, os.path.abspath(__file__), "--client", "--case", case,
                 "--pty", pty_path, "--shim", shim],
                env=client_env, capture_output=True, text=True, timeout=CLIENT_TIMEOUT_S)
            sys.stdout.write(client.stdout)
            sys.stderr.write(client.stderr)
            check(client.returncode == 0,
                  f"the {case} client exited with {client.returncode}")
        except BaseException:
            stop_daemon(daemon)
            with open(log_path, encoding="utf-8", errors="replace") as f:
                sys.stderr.write("rigsimd log:\n" + f.read())
            raise
        status = stop_daemon(daemon)
        check(status == 0, f"rigsimd exited with {status} after SIGTERM, expected 0")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", choices=("shim", "bare"), required=True)
    parser.add_argument("--rigsimd", help="the rigsimd binary")
    parser.add_argument("--shim", required=True, help="librigsim_modemlines.so")
    parser.add_argument("--client", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--pty", help=argparse.SUPPRESS)
    args = parser.parse_args()
    try:
        if args.client:
            run_client(args.case, args.pty, args.shim)
        else:
            check(args.rigsimd, "--rigsimd is required")
            run_test(args.case, args.rigsimd, args.shim)
    except TestFailure as e:
        role = "client" if args.client else "test"
        print(f"FAIL ({args.case} {role}): {e}", file=sys.stderr)
        return 1
    if not args.client:
        print(f"PASS: APT over pyserial, {args.case} case")
    return 0


if __name__ == "__main__":
    sys.exit(main())
