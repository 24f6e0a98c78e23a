"""rigsim-replay: play the client side of a rigsim-tap recording against rigsim and compare every
answer with the unit's (docs/conformance.md, "Replaying a recording").

    python3 -m rigsim.replay FILE (--rig RIG.json [--rigsimd PATH] | --control URL [--token-file F])
                             --device NAME [--junit OUT]
                             [--ignore FIELD]... [--tolerance FIELD=AMOUNT]... [--timeout S]
                             [--via tcp|pty] [--timing]
    python3 -m rigsim.replay FILE --learn --out RIG.json [--device NAME]

Starts rigsimd on RIG.json with its clock paused (or pauses the running daemon at URL), connects
to device NAME once per connection of the recording (over its pty when the client used one, else
TCP; --via chooses), and walks the
recording in order: the clock is stepped to each line's time (the gaps between the recorded
times), each frame the client sent is sent, and each frame the unit sent is read from rigsim and
compared with it, field by field as rigsim's codec reads both (the daemon's wire log decodes
rigsim's; the tap decoded the unit's). A reply (a line with "reply_to") is awaited a millisecond of
clock at a time, and its latency on rigsim's clock compared with the spread of the unit's latencies
for the same request: one outside it by more than a millisecond is reported, and counts as a
difference with --timing. Fields that may differ are ignored:
serial numbers by default (DEFAULT_IGNORED), and each --ignore FIELD; --tolerance FIELD=AMOUNT
takes numbers within AMOUNT as equal (a position read while the stage moves). Prints one line per
difference (connection, the recording's seq and time, the message, the field, the unit's value,
rigsim's value) and exits 0 when conformant, 1 with differences, 2 on bad input (the recording's
file and line named). --junit OUT writes a JUnit XML report, one test case per answer.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import select
import socket
import sys
import termios
import time
import tty
from collections.abc import Iterator, Sequence
from typing import Any, Callable, Union
from xml.sax.saxutils import escape, quoteattr

from rigsim.control import ControlClient, ControlError
from rigsim.daemon import Endpoint, Rigsim, RigsimError

DEFAULT_IGNORED = ("serial_number",)
PROTOCOLS = ("apt", "mcs", "mcs2")


class RecordingError(Exception):
    """The recording cannot be replayed: the message names the file and the line."""


def _check(cond: bool, where: str, what: str) -> None:
    if not cond:
        raise RecordingError(f"{where}: {what}")


def read_recording(path: str) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    """The header and the lines of a version 1 recording, every line checked (RecordingError)."""
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise RecordingError(f"{path}: cannot read the recording: {e}") from e
    lines = text.split("\n")
    _check(text.endswith("\n"), f"{path}:{len(lines)}", "the last line is cut (no line end): a recording cut mid-line")
    records: list[dict[str, Any]] = []
    header: dict[str, Any] = {}
    last_t = 0
    for number, line in enumerate(lines[:-1], 1):
        where = f"{path}:{number}"
        try:
            obj = json.loads(line)
        except ValueError as e:
            raise RecordingError(f"{where}: not JSON ({e})") from e
        _check(isinstance(obj, dict), where, "expected a JSON object")
        if number == 1:
            _check(obj.get("rigsim_recording") == 1, where,
                   "not a rigsim recording of version 1 (the first line has no \"rigsim_recording\": 1)")
            _check(obj.get("protocol") in PROTOCOLS, where, f"protocol: expected one of {', '.join(PROTOCOLS)}")
            header = obj
            continue
        _check(obj.get("seq") == len(records), where, f"seq: expected {len(records)}, got {obj.get('seq')!r}")
        t = obj.get("t_us")
        _check(isinstance(t, int) and t >= last_t, where, "t_us: expected an integer time not before the last line's")
        last_t = t
        _check(isinstance(obj.get("conn"), int) and obj["conn"] >= 0, where, "conn: expected a connection number")
        if "event" in obj:
            _check(isinstance(obj["event"], str), where, "event: expected a name")
        else:
            _check(obj.get("dir") in ("in", "out"), where, "dir: expected \"in\" or \"out\"")
            data = obj.get("bytes")
            _check(isinstance(data, str) and len(data) % 2 == 0, where, "bytes: expected hex digits, two a byte")
            try:
                obj["raw"] = bytes.fromhex(data)
            except ValueError as e:
                raise RecordingError(f"{where}: bytes: not hex ({e})") from e
            _check(isinstance(obj.get("decoded"), dict) or obj.get("partial") is True, where,
                   "expected \"decoded\" (an object) or \"partial\": true")
            if "latency_us" in obj or "reply_to" in obj:
                _check(obj.get("dir") == "out" and isinstance(obj.get("latency_us"), int) and obj["latency_us"] >= 0
                       and isinstance(obj.get("reply_to"), int) and 0 <= obj["reply_to"] < len(records), where,
                       "latency_us, reply_to: expected both on an out frame, a time and an earlier line's seq")
        obj["line"] = number
        records.append(obj)
    _check(bool(header), f"{path}:1", "empty recording")
    return header, records


class _Connection:
    """One client connection to rigsim: a TCP socket, or the device's pty opened raw."""

    def __init__(self, endpoint: Any, via: str, timeout_s: float):
        self.timeout_s = timeout_s
        self.sock: socket.socket | None = None
        self.fd = -1
        if via == "pty":
            self.fd = os.open(endpoint.pty, os.O_RDWR | os.O_NOCTTY)
            tty.setraw(self.fd, termios.TCSANOW)
        else:
            self.sock = socket.create_connection(endpoint.address, timeout=timeout_s)

    def send(self, data: bytes) -> None:
        if self.sock:
            self.sock.sendall(data)
            return
        view = memoryview(data)
        while view:
            view = view[os.write(self.fd, view):]

    def recv(self, wait_s: float) -> bytes | None:
        """What has come within `wait_s` seconds: None when nothing has; ConnectionError when closed."""
        fileno = self.sock.fileno() if self.sock else self.fd
        if not select.select([fileno], [], [], wait_s)[0]:
            return None
        chunk = self.sock.recv(4096) if self.sock else os.read(self.fd, 4096)
        if not chunk:
            raise ConnectionError("rigsim closed the connection")
        return chunk

    def close(self) -> None:
        if self.sock:
            self.sock.close()
        elif self.fd >= 0:
            os.close(self.fd)
        self.sock, self.fd = None, -1


def _take_frame(protocol: str, buf: bytearray) -> bytes | None:
    """The first whole frame of `protocol` in `buf`, taken out of it; None while it is not whole."""
    if protocol == "apt":
        if len(buf) < 6:
            return None
        size = 6 + (int.from_bytes(buf[2:4], "little") if buf[4] & 0x80 else 0)
        if len(buf) < size:
            return None
    else:
        if b"\n" not in buf:
            return None
        size = buf.index(b"\n") + 1
    frame = bytes(buf[:size])
    del buf[:size]
    return frame


def _read_frame(conn: _Connection, protocol: str, buf: bytearray) -> bytes | None:
    """One frame of `protocol` from `conn` within its timeout (None when none comes)."""
    while (frame := _take_frame(protocol, buf)) is None:
        chunk = conn.recv(conn.timeout_s)
        if chunk is None:
            return None
        buf.extend(chunk)
    return frame


# What the replay drives: a rigsimd it started (Rigsim), or a running daemon's control API.
_Daemon = Union[Rigsim, ControlClient]


@contextlib.contextmanager
def _daemon(rig_path: str | None, rigsimd: str | None, control: str | None,
            token: str | None) -> Iterator[tuple[_Daemon, Callable[[str], Endpoint]]]:
    """The daemon to replay against, its clock paused, and how to find a device's endpoints: a
    rigsimd started on `rig_path`, or the running one whose control API is at `control` (its
    clock is paused for the replay and set running again after it if it ran)."""
    if control is None:
        with Rigsim(rig_path, rigsimd=rigsimd, args=["--paused"]) as rig:
            yield rig, rig.endpoint
        return
    client = ControlClient(control, token=token)

    def endpoint(name: str) -> Endpoint:
        for d in client.rig().get("devices", []):
            if d.get("name") == name:
                return Endpoint(name, d.get("protocol", ""), d.get("model", ""), d.get("tcp", ""), d.get("pty", ""))
        raise RecordingError(f"the daemon at {client.url} has no device {name!r}")

    ran = not client.clock().get("paused", False)
    client.pause()
    try:
        yield client, endpoint
    finally:
        if ran:
            client.resume()


def _until_read(rig: _Daemon, device: str, before: int, timeout_s: float) -> None:
    """Waits until the daemon has read a frame sent after wire log entry `before`: its entry is
    in the log, or the link holds it for the next USB frame. A step sent sooner could reach the
    daemon first and move the clock under the request."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if rig.log_cursor(device) > before:
            return
        link = rig.state(device).get("link") or {}
        if link.get("held_requests", 0) > 0:
            return
        time.sleep(0.001)


# A step of the clock while a reply is awaited, and how long the replay waits for rigsim's bytes
# after each: the step's answer comes after the bytes it released are written.
_AWAIT_STEP_MS = 1
_AWAIT_PROBE_S = 0.01


def _await_frame(conn: _Connection, protocol: str, buf: bytearray, rig: _Daemon,
                 limit_ms: int) -> tuple[bytes | None, int]:
    """A reply: the clock stepped a millisecond at a time until a whole frame has come (or
    `limit_ms` have passed); the frame and the milliseconds stepped."""
    stepped = 0
    while True:
        frame = _take_frame(protocol, buf)
        if frame is not None:
            return frame, stepped
        chunk = conn.recv(_AWAIT_PROBE_S)
        if chunk is not None:
            buf.extend(chunk)
            continue
        if stepped >= limit_ms:
            return None, stepped
        rig.step(_AWAIT_STEP_MS)
        stepped += _AWAIT_STEP_MS


def _fields(decoded: dict[str, Any], protocol: str, queries: list[list[str]] | None = None) -> dict[str, Any]:
    """What is compared of a decoded frame: its fields (and name); an MCS2 answer line's answers
    named by the queries that asked for them (`CHAN0:POS`), else its text."""
    if protocol == "mcs2":
        text = decoded.get("text")
        answers = [a.strip() for a in text.split(";")] if isinstance(text, str) else []
        if queries and len(queries) == len(answers):
            return {":".join(q): a for q, a in zip(queries, answers)}
        return {"text": text}
    out = dict(decoded.get("fields") or {})
    out["(message)"] = decoded.get("name") or decoded.get("command")
    return out


def _number(text: Any) -> float | None:
    if isinstance(text, bool):
        return None
    if isinstance(text, (int, float)):
        return float(text)
    try:
        return float(str(text).strip())
    except ValueError:
        return None


def _rule(field: str, rules: dict[str, Any] | Sequence[str]) -> str | None:
    """The rule's key that names `field`: the field itself, or one keyword of an MCS2 answer's
    query path (`POS` names `CHAN0:POS`)."""
    if field in rules:
        return field
    for keyword in field.split(":"):
        if keyword in rules:
            return keyword
    return None


def _is_position(field: str) -> bool:
    """A stage's position: APT's and MCS's `position` (MCS's `angle`), an MCS2 channel's `POS`."""
    return field in ("position", "angle") or field.split(":")[-1] == "POS"


def _position_key(fields: dict[str, Any], field: str) -> str:
    """Whose position `field` of an answer is: its channel and the field."""
    channel = fields.get("chan_ident", fields.get("channelIndex", ""))
    return f"{channel}/{field}"


def position_speeds(records: list[dict[str, Any]], protocol: str) -> dict[str, float]:
    """How fast each stage's position may change, in its units per µs: the fastest change between
    two consecutive readings of the unit's, or (MCS2) the fastest velocity the client set
    (`:CHAN#:VEL`, pm/s)."""
    speed: dict[str, float] = {}
    last: dict[str, tuple[int, float]] = {}
    queries: list[list[str]] = []
    for r in records:
        if "event" in r:   # a new connection: a power cycle or a reset may lie between
            last.clear()
            continue
        if "decoded" not in r:
            continue
        if r["dir"] == "in":
            if _sets_position(r["decoded"], protocol):   # a jump, not a speed
                last.clear()
            if protocol == "mcs2":
                commands = _mcs2_commands(r["decoded"].get("text", ""))
                queries = [p for p, q, _ in commands if q]
                for path, query, argument in commands:
                    v = _number(argument)
                    if not query and len(path) == 2 and path[1] == "VEL" and v is not None:
                        key = f"/{path[0]}:POS"
                        speed[key] = max(speed.get(key, 0.0), abs(v) / 1e6)
            continue
        fields = _fields(r["decoded"], protocol, queries)
        queries = []
        for field, value in fields.items():
            n = _number(value)
            if not _is_position(field) or n is None:
                continue
            key = _position_key(fields, field)
            if key in last and r["t_us"] > last[key][0]:
                speed[key] = max(speed.get(key, 0.0), abs(n - last[key][1]) / (r["t_us"] - last[key][0]))
            last[key] = (r["t_us"], n)
    return speed


def _sets_position(decoded: dict[str, Any], protocol: str) -> bool:
    """Whether a client frame sets a position counter (APT MOT_SET_POSCOUNTER, ENCCOUNTER; MCS
    `SP`; MCS2 `:CHAN#:POS <value>`) or resets the unit (MCS2 `*RST`)."""
    if protocol == "apt":
        return decoded.get("name") in ("MGMSG_MOT_SET_POSCOUNTER", "MGMSG_MOT_SET_ENCCOUNTER")
    if protocol == "mcs":
        return decoded.get("command") == "SP"
    text = str(decoded.get("text", ""))
    return "*RST" in text.upper() or any(not q and p[-1:] == ["POS"] for p, q, _ in _mcs2_commands(text))


# What the replay's clock may be off from the unit's when a reading is taken: the part of a
# millisecond its steps do not reproduce.
POSITION_WINDOW_US = 1000


def _fields_differ(unit: dict[str, Any], ours: dict[str, Any]) -> bool:
    """Whether some field of the two answers differs (reported, or let pass by a rule: ignored,
    within a tolerance): then their bytes differ for that reason."""
    return any(unit.get(f) != ours.get(f) for f in set(unit) | set(ours))


def _same(field: str, unit: Any, ours: Any, tolerance: dict[str, float]) -> bool:
    """Equal, or two numbers within the tolerance a rule gives the field."""
    if unit == ours:
        return True
    key = _rule(field, tolerance)
    if key is None:
        return False
    nu, no = _number(unit), _number(ours)
    return nu is not None and no is not None and abs(nu - no) <= tolerance[key]


def _request_key(request: dict[str, Any], protocol: str) -> str:
    """What a request is, for the spread of its replies' latencies: the APT message's name, the MCS
    command's mnemonic, an MCS2 line's queries."""
    decoded = request.get("decoded") or {}
    if protocol == "mcs2":
        text = decoded.get("text", "")
        return "; ".join(":".join(q) for q in _mcs2_queries(text)) or str(text)
    return str(decoded.get("command") or decoded.get("name") or request.get("bytes", ""))


def latency_spread(records: list[dict[str, Any]], protocol: str) -> dict[str, tuple[int, int]]:
    """The shortest and the longest reply latency (µs) the unit showed for each kind of request."""
    by_seq = {r["seq"]: r for r in records}
    spread: dict[str, tuple[int, int]] = {}
    for r in records:
        if "latency_us" in r and r.get("reply_to") in by_seq:
            key = _request_key(by_seq[r["reply_to"]], protocol)
            lo, hi = spread.get(key, (r["latency_us"], r["latency_us"]))
            spread[key] = (min(lo, r["latency_us"]), max(hi, r["latency_us"]))
    return spread


# A reply's latency on rigsim's clock is within the unit's spread when it is no more than this
# outside it: the replay steps the clock a millisecond at a time.
TIMING_SLACK_US = 1000


def replay(recording: str, rig_path: str | None, device: str, rigsimd: str | None = None,
           ignore: Sequence[str] = DEFAULT_IGNORED, timeout_s: float = 2.0,
           tolerance: dict[str, float] | None = None, via: str | None = None,
           timing_slack_us: int = TIMING_SLACK_US, control: str | None = None,
           token: str | None = None) -> tuple[list[dict[str, Any]], int]:
    """The differences, and the number of answers compared, replaying against a rigsimd started
    on `rig_path` or the running daemon whose control API is at `control`. A reply whose latency
    on rigsim's clock falls outside the unit's spread is a difference with "timing": True."""
    tolerance = tolerance or {}
    header, records = read_recording(recording)
    protocol = header["protocol"]
    spread = latency_spread(records, protocol)
    by_seq = {r["seq"]: r for r in records}
    if via is None:
        via = "pty" if str(header.get("listen", "")).startswith("pty:") else "tcp"
    with _daemon(rig_path, rigsimd, control, token) as (rig, endpoint_of):
        endpoint = endpoint_of(device)
        if endpoint.protocol != protocol:
            raise RecordingError(f"{recording}:1: a recording of protocol {protocol}, but device {device} "
                                 f"speaks {endpoint.protocol}")
        if via == "pty" and not endpoint.pty:
            raise RecordingError(f"{recording}:1: the client used a pty, but device {device} has none "
                                 "(--via tcp replays over TCP)")
        differences: list[dict[str, Any]] = []
        pairs: list[tuple[dict[str, Any], bytes | None]] = []
        conn: _Connection | None = None
        conn_id = None
        buf = bytearray()
        queries: list[list[str]] = []
        clock_us = records[0]["t_us"] if records else 0   # the recording's time rigsim's clock is at
        sent_us: dict[int, int] = {}   # a request's seq -> clock_us when it was sent
        try:
            for r in records:
                awaited = r.get("dir") == "out" and not r.get("partial") and r.get("reply_to") in sent_us
                gap_ms = (r["t_us"] - clock_us) // 1000
                if gap_ms > 0 and not awaited:
                    rig.step(int(gap_ms))
                    clock_us += gap_ms * 1000
                if "event" in r:
                    if r["event"] == "disconnect" and conn:
                        conn.close()
                        conn = None
                    continue
                if r["conn"] != conn_id or conn is None:
                    if conn:
                        conn.close()
                    conn = _Connection(endpoint, via, timeout_s)
                    conn_id = r["conn"]
                    buf = bytearray()
                if r["dir"] == "in":
                    before = rig.log_cursor(device) if not r.get("partial") else None
                    conn.send(r["raw"])
                    if before is not None:
                        _until_read(rig, device, before, timeout_s)
                    sent_us[r["seq"]] = clock_us
                    if protocol == "mcs2":
                        queries = _mcs2_queries(r["decoded"].get("text", "")) if "decoded" in r else []
                    continue
                if r.get("partial"):
                    continue
                got: bytes | None
                try:
                    if awaited:
                        limit_ms = max(300, 2 * r["latency_us"] // 1000 + 100)
                        got, stepped = _await_frame(conn, protocol, buf, rig, limit_ms)
                        clock_us += stepped * 1000
                        key = _request_key(by_seq[r["reply_to"]], protocol)
                        ours = clock_us - sent_us[r["reply_to"]]
                        lo, hi = spread[key]
                        if got is not None and not lo - timing_slack_us <= ours <= hi + timing_slack_us:
                            differences.append({"conn": r["conn"], "seq": r["seq"], "t_ms": r["t_us"] / 1000,
                                                "line": r["line"], "message": key, "field": "(latency)",
                                                "unit": f"{lo / 1000:.3f}..{hi / 1000:.3f} ms",
                                                "rigsim": f"{ours / 1000:.0f} ms", "timing": True})
                    else:
                        got = _read_frame(conn, protocol, buf)
                except (socket.timeout, ConnectionError, OSError):
                    got = None
                pairs.append((dict(r, queries=queries), got))
                queries = []
        finally:
            if conn:
                conn.close()
        speeds = position_speeds(records, protocol)
        log = rig.log(device)
        outs = [e for e in log["entries"] if e["direction"] == "out"]
        k = 0
        for r, got in pairs:
            where = {"conn": r["conn"], "seq": r["seq"], "t_ms": r["t_us"] / 1000, "line": r["line"]}
            unit = _fields(r["decoded"], protocol, r.get("queries"))
            name = unit.get("(message)") or r["decoded"].get("text")
            if got is None:
                differences.append(dict(where, message=name, field="(answer)", unit=r["bytes"], rigsim="none"))
                continue
            if got == r["raw"]:
                continue
            at = k
            while at < len(outs) and bytes.fromhex(outs[at]["hex"]) != got:
                at += 1
            if at == len(outs):
                # Not in the wire log (it keeps the last 1000 frames each way): the bytes alone.
                differences.append(dict(where, message=name, field="(bytes)", unit=r["bytes"], rigsim=got.hex()))
                continue
            ours = _fields(outs[at].get("decoded", {}), protocol, r.get("queries"))
            k = at + 1
            found = len(differences)
            for field in sorted(set(unit) | set(ours)):
                rules = tolerance
                if _is_position(field) and _rule(field, tolerance) is None:
                    # A position read while the stage moves: within what it covers in the window
                    # and the reply's own latency, at its fastest (--tolerance FIELD=0 turns it off).
                    window = POSITION_WINDOW_US + int(r.get("latency_us", 0))
                    rules = dict(tolerance, **{field: speeds.get(_position_key(unit, field), 0.0) * window})
                if _rule(field, ignore) is not None or _same(field, unit.get(field), ours.get(field), rules):
                    continue
                differences.append(dict(where, message=name, field=field, unit=unit.get(field),
                                        rigsim=ours.get(field)))
            if len(differences) == found and not _fields_differ(unit, ours):
                # The bytes differ where the codec reads no field (a reserved word, the tail of a
                # string after its end): the bytes themselves.
                differences.append(dict(where, message=name, field="(bytes)", unit=r["bytes"], rigsim=got.hex()))
        differences.sort(key=lambda d: int(d["seq"]))
        return differences, len(pairs)


# ---- learning a rig from a recording ----

_ALIASES = {"PROPERTY": "PROP", "DEVICE": "DEV", "SNUMBER": "SNUM", "NOCHANNELS": "NOCH", "CHANNEL": "CHAN",
            "PTYPE": "PTYP", "CODE": "CODE", "POSITION": "POS", "STATE": "STAT", "TARGET": "TARG",
            "CURRENT": "CURR", "SYSTEM": "SYST", "ERROR": "ERR"}


def _mcs2_commands(text: str) -> list[tuple[list[str], bool, str]]:
    """The commands of one MCS2 message: each keyword path in short upper case (`CHAN0`, `PTYP`),
    the optional root dropped, relative commands resolved at the level of the one before (6.2.3);
    whether it is a query; its argument text."""
    level: list[str] = []
    out: list[tuple[list[str], bool, str]] = []
    for command in text.split(";"):
        command = command.strip()
        if not command or command.startswith("*"):
            if command.upper().startswith("*IDN?"):
                out.append((["*IDN"], True, ""))
            continue
        head, _, argument = command.partition(" ")
        query = head.endswith("?")
        head = head.rstrip("?")
        words = []
        for w in head.strip(":").split(":"):
            letters = w.rstrip("0123456789").upper()
            words.append(_ALIASES.get(letters, letters) + w[len(letters):])
        if words and words[0] == "PROP":
            words = words[1:]
        path = words if command.startswith(":") or not level else level + words
        level = path[:-1]
        out.append((path, query, argument.strip()))
    return out


def _mcs2_queries(text: str) -> list[list[str]]:
    """The queries of one MCS2 message as keyword paths (_mcs2_commands)."""
    return [path for path, query, _ in _mcs2_commands(text) if query]


def _learn_mcs2(records: list[dict[str, Any]], device: dict[str, Any]) -> None:
    section: dict[str, Any] = {}
    types: dict[int, int] = {}
    off_mark: dict[int, bool] = {}   # the first state word read: REFERENCE_MARK (bit 15) clear
    count = 0
    pending: list[list[str]] = []
    for r in records:
        if "event" in r or r.get("partial"):
            continue
        text = r["decoded"].get("text", "")
        if r["dir"] == "in":
            pending = _mcs2_queries(text)
            continue
        answers = [a.strip() for a in text.split(";")]
        if len(answers) != len(pending):
            pending = []
            continue
        for path, answer in zip(pending, answers):
            if path == ["DEV", "SNUM"]:
                section["serial_number"] = answer.strip('"')
            elif path == ["*IDN"] and answer.count(",") >= 3:
                section["serial_number"] = answer.split(",")[2]
            elif path == ["DEV", "NOCH"] and answer.isdigit():
                count = int(answer)
            elif len(path) >= 2 and path[0].startswith("CHAN") and path[0][4:].isdigit() and \
                    path[1:] in (["PTYP"], ["PTYP", "CODE"]) and answer.isdigit() and int(answer) >= 300:
                types[int(path[0][4:])] = int(answer)
            elif len(path) == 2 and path[0].startswith("CHAN") and path[0][4:].isdigit() and \
                    path[1] in ("STAT", "STATE") and answer.lstrip("-").isdigit():
                off_mark.setdefault(int(path[0][4:]), not int(answer) & 0x8000)
        pending = []
    count = max([count, 1] + [c + 1 for c in types] + [c + 1 for c in off_mark])
    channels: list[dict[str, Any]] = [{} for _ in range(count)]
    for c, t in types.items():
        channels[c]["positioner_type"] = t
    for c, off in off_mark.items():
        if off:   # off its mark at power-up: 5 mm (5°) past it, half way to the default end stop
            channels[c]["start_position"] = 5_000_000_000   # (the physical start itself is not seen)
    section["channels"] = channels
    device["mcs2"] = section


def _learn_mcs(records: list[dict[str, Any]], device: dict[str, Any]) -> None:
    section: dict[str, Any] = {}
    count = 1
    for r in records:
        if r.get("dir") != "out" or r.get("partial"):
            continue
        text = r["decoded"].get("text", "").strip(":\n")
        version = text[2:].split(",") if text.startswith("IV") else []
        if text.startswith("ID") and text[2:].isdigit():
            section["system_id"] = int(text[2:])
        elif len(version) == 3 and all(v.isdigit() for v in version):
            section["interface_version"] = ".".join(version)
            # The newest firmware generation whose version is not above the unit's (docs/config.md).
            numbers = tuple(int(v) for v in version)
            device["firmware"] = "2.0.1" if numbers >= (2, 0, 1) else "1.2.44"
        elif text.startswith("N") and text[1:].isdigit():
            count = max(count, int(text[1:]))
    section["channels"] = [{} for _ in range(count)]
    device["mcs"] = section


# The parameter blocks a motor controller keeps in its EEPROM (MOT_SET_EEPROMPARAMS, p. 60), whose
# GET a learnt rig's "eeprom" replays as the SET (its ID is the GET's less 2): MotorModule::Saved
# in emulator/apt/motor_module.hpp.
# HW_GET_INFO's stage type word (data 76) of a TDC001/KDC101 at the later issue: the stage it drives.
_DC_STAGE_TYPES = {6: "PRM1-Z8", 7: "MTS25-Z8", 8: "MTS50-Z8", 9: "Z825B", 10: "Z812B"}
_MOTOR_MODELS = ("TDC001", "KDC101", "TST001", "KST101", "BSC203", "BBD203", "K10CR1", "LTS150", "LTS300", "KBD101")
_MOTOR_SAVED = tuple("MGMSG_MOT_GET_" + n for n in (
    "VELPARAMS", "JOGPARAMS", "GENMOVEPARAMS", "MOVERELPARAMS", "MOVEABSPARAMS", "HOMEPARAMS", "LIMSWITCHPARAMS",
    "DCPIDPARAMS", "AVMODES", "POTPARAMS", "BUTTONPARAMS", "PMDPOSITIONLOOPPARAMS", "PMDMOTOROUTPUTPARAMS",
    "PMDTRACKSETTLEPARAMS", "PMDPROFILEMODEPARAMS", "PMDCURRENTLOOPPARAMS", "PMDSETTLEDCURRENTLOOPPARAMS",
    "PMDSTAGEAXISPARAMS"))


def _learn_apt(records: list[dict[str, Any]], device: dict[str, Any]) -> None:
    """The model and serial number (HW_GET_INFO), and, for a motor controller, each parameter block
    the client read before it set it: the unit's power-up values, as its EEPROM (apt.eeprom)."""
    section: dict[str, Any] = {}
    eeprom: dict[str, str] = {}
    set_first: set[str] = set()   # blocks the client set before reading them: not the unit's own
    for r in records:
        decoded = r.get("decoded") or {}
        name = str(decoded.get("name", ""))
        if r.get("dir") == "in" and "_SET_" in name:
            set_first.add(name.replace("_SET_", "_GET_"))
        if r.get("dir") != "out":
            continue
        if name == "MGMSG_HW_GET_INFO" and "model" not in device:
            fields = decoded.get("fields") or {}
            if isinstance(fields.get("model_number"), str):
                device["model"] = fields["model_number"]
            if isinstance(fields.get("serial_number"), int):
                section["serial_number"] = fields["serial_number"]
            data = r["raw"][6:]
            if len(data) >= 84:
                # The later protocol issue's fields (docs/protocol/apt.md, "Firmware generations"):
                # the stage type word at data 76 and the hardware version at 78, where the 2012
                # manual's 64-character notes end in zeros.
                stage_type = int.from_bytes(data[76:78], "little")
                if stage_type or int.from_bytes(data[78:80], "little"):
                    device["firmware"] = "issue-44.1"
                if stage_type in _DC_STAGE_TYPES:
                    section["stage"] = _DC_STAGE_TYPES[stage_type]
        elif name in _MOTOR_SAVED and name not in set_first and len(r["raw"]) > 6:
            source = int(str(decoded.get("source", "0x50")), 16)
            bay = source - 0x21 if 0x21 <= source <= 0x2A else 0
            key = "bay%d/0x%04x" % (bay, int(str(decoded.get("id")), 16) - 2)
            eeprom.setdefault(key, r["raw"][6:].hex())
    if "model" not in device:
        raise RecordingError("no HW_GET_INFO answer in the recording: the unit's model is not known")
    if eeprom and device["model"] in _MOTOR_MODELS:
        section["eeprom"] = eeprom
    device["apt"] = section


def learn(recording: str, name: str | None = None) -> dict[str, Any]:
    """A rig with one device as the recording shows the unit: MCS2 its serial number, channel count
    and the positioner types read; MCS its system ID and channel count; APT its model and serial
    number (HW_GET_INFO). What the session did not read keeps rigsim's defaults."""
    header, records = read_recording(recording)
    protocol = header["protocol"]
    device: dict[str, Any] = {"name": name or protocol + "0", "protocol": protocol}
    try:
        {"mcs2": _learn_mcs2, "mcs": _learn_mcs, "apt": _learn_apt}[protocol](records, device)
    except RecordingError as e:
        raise RecordingError(f"{recording}: {e}") from e
    _learn_link(header, records, device)
    return {"devices": [device]}


# Replies of one kind of request --learn needs to see the latency timer in their spread.
_LEARN_MIN_REPLIES = 5


def _learn_link(header: dict[str, Any], records: list[dict[str, Any]], device: dict[str, Any]) -> None:
    """A unit on a serial line answers through a USB-serial chip, whose latency timer spreads the
    replies to one kind of request over a window as wide as the timer (a reply waits for the
    timer's next expiry, at any phase): the widest spread of one kind's latencies is the timer
    (docs/config.md, "The link model"). The line's pace as well where the rate is the unit's own
    (APT: 115200; MCS: its factory 9600)."""
    to = str(header.get("to", ""))
    if not to.startswith("serial:") or not any("latency_us" in r for r in records):
        return
    link: dict[str, Any] = {}
    # The timer from the kinds of request asked often enough to show it: the spread of their
    # latencies up to the 90th percentile (one reply the machine delayed does not count), of which
    # a uniform phase shows 90 %. With too few, Linux's default (16 ms) stays.
    by_seq = {r["seq"]: r for r in records}
    kinds: dict[str, list[int]] = {}
    for r in records:
        if "latency_us" in r and r["reply_to"] in by_seq:
            kinds.setdefault(_request_key(by_seq[r["reply_to"]], header["protocol"]), []).append(r["latency_us"])
    widths = []
    for latencies in kinds.values():
        if len(latencies) >= _LEARN_MIN_REPLIES:
            ordered = sorted(latencies)
            widths.append((ordered[(len(ordered) - 1) * 9 // 10] - ordered[0]) / 0.9)
    if widths:
        link["latency_timer_ms"] = min(255, max(1, round(max(widths) / 1000)))
    if not str(header.get("listen", "")).startswith("pty:"):
        link["tcp"] = True   # the client came over TCP: the replay will too
    device["link"] = link
    baud = to.rsplit(",", 1)[1] if "," in to else "115200"
    if (device["protocol"] == "apt" and baud == "115200") or (device["protocol"] == "mcs" and baud == "9600"):
        device["faithful_timing"] = True


def write_junit(path: str, recording: str, differences: list[dict[str, Any]], compared: int) -> None:
    by_seq: dict[int, list[dict[str, Any]]] = {}
    for d in differences:
        by_seq.setdefault(d["seq"], []).append(d)
    cases = []
    for seq, ds in sorted(by_seq.items()):
        text = "\n".join(f"{d['field']}: unit {d['unit']!r}, rigsim {d['rigsim']!r}" for d in ds)
        cases.append(f'  <testcase name={quoteattr("seq %d %s" % (seq, ds[0]["message"]))}>'
                     f'<failure message={quoteattr(ds[0]["field"])}>{escape(text)}</failure></testcase>')
    cases.append(f'  <testcase name={quoteattr("%d answers compared" % compared)}/>')
    with open(path, "w", encoding="utf-8") as f:
        f.write('<?xml version="1.0" encoding="UTF-8"?>\n')
        f.write(f'<testsuite name={quoteattr("rigsim-replay " + os.path.basename(recording))} '
                f'tests="{len(cases)}" failures="{len(by_seq)}">\n' + "\n".join(cases) + "\n</testsuite>\n")


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="rigsim-replay", description=__doc__.split("\n\n")[0])
    parser.add_argument("recording")
    parser.add_argument("--rig", help="the rig JSON to replay against (a rigsimd is started on it)")
    parser.add_argument("--control", metavar="URL",
                        help="instead of --rig: a running rigsimd's control API (http://HOST:PORT); its clock is "
                             "paused for the replay")
    parser.add_argument("--token", help="--control: the daemon's control token (default: $RIGSIM_CONTROL_TOKEN)")
    parser.add_argument("--token-file", metavar="FILE", help="--control: read the control token from FILE")
    parser.add_argument("--device", help="the device of the rig the recording's unit is (--learn: its name)")
    parser.add_argument("--learn", action="store_true", help="write a rig learnt from the recording to --out")
    parser.add_argument("--out", help="--learn: the rig JSON to write")
    parser.add_argument("--rigsimd", default=None, help="the rigsimd binary (default: $RIGSIMD, PATH)")
    parser.add_argument("--junit", default=None, help="write a JUnit XML report here")
    parser.add_argument("--ignore", action="append", default=[], help="a field that may differ (repeatable)")
    parser.add_argument("--timeout", type=float, default=2.0, help="seconds to wait for each answer")
    parser.add_argument("--tolerance", action="append", default=[], metavar="FIELD=AMOUNT",
                        help="numbers of FIELD within AMOUNT are equal (repeatable; MCS2: a query's keyword, POS)")
    parser.add_argument("--via", choices=("tcp", "pty"), default=None,
                        help="how to reach rigsim (default: its pty when the recorded client used a pty, else TCP)")
    parser.add_argument("--timing", action="store_true",
                        help="a reply whose latency is outside the unit's spread is a difference (exit 1)")
    parser.add_argument("--timing-slack", type=float, default=TIMING_SLACK_US / 1000, metavar="MS",
                        help="how far outside the unit's spread a reply may be, in ms (default 1: the replay's step)")
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:
        return 2 if e.code else 0
    if args.learn:
        if not args.out:
            print("rigsim-replay: --learn needs --out RIG.json", file=sys.stderr)
            return 2
        try:
            rig = learn(args.recording, args.device)
            with open(args.out, "w", encoding="utf-8") as f:
                json.dump(rig, f, indent=2)
                f.write("\n")
        except (RecordingError, OSError) as e:
            print(f"rigsim-replay: {e}", file=sys.stderr)
            return 2
        return 0
    tolerance: dict[str, float] = {}
    for t in args.tolerance:
        name, _, amount = t.partition("=")
        if not name or _number(amount) is None:
            print(f"rigsim-replay: --tolerance: expected FIELD=AMOUNT, got {t!r}", file=sys.stderr)
            return 2
        tolerance[name] = float(_number(amount) or 0)
    if not 0 <= args.timing_slack <= 60_000:   # also refuses nan
        print(f"rigsim-replay: --timing-slack: expected 0..60000 ms, got {args.timing_slack}", file=sys.stderr)
        return 2
    if not args.device or bool(args.rig) == bool(args.control):
        print("rigsim-replay: --device and one of --rig and --control are required (or --learn --out)",
              file=sys.stderr)
        return 2
    token = args.token
    if args.token_file:
        try:
            with open(args.token_file, encoding="utf-8") as f:
                token = f.readline().strip()
        except OSError as e:
            print(f"rigsim-replay: --token-file: cannot read {args.token_file}: {e.strerror}", file=sys.stderr)
            return 2
    try:
        differences, compared = replay(args.recording, args.rig, args.device, args.rigsimd,
                                       list(DEFAULT_IGNORED) + args.ignore, args.timeout, tolerance, args.via,
                                       round(args.timing_slack * 1000), args.control, token)
    except (RecordingError, RigsimError, ControlError, OSError, termios.error) as e:
        print(f"rigsim-replay: {e}", file=sys.stderr)
        return 2
    timing = [d for d in differences if d.get("timing")]
    if not args.timing:
        differences = [d for d in differences if not d.get("timing")]
    for d in differences + ([] if args.timing else timing):
        print(f"{'timing: ' if d.get('timing') and not args.timing else ''}"
              f"conn {d['conn']} seq {d['seq']} at {d['t_ms']:.3f} ms (line {d['line']}) {d['message']}: "
              f"{d['field']}: unit {d['unit']!r}, rigsim {d['rigsim']!r}")
    if args.junit:
        write_junit(args.junit, args.recording, differences, compared)
    print(f"rigsim-replay: {compared} answers compared, {len(differences)} difference(s), "
          f"{len(timing)} reply time(s) outside the unit's spread"
          f"{'' if args.timing else ' (differences with --timing)'}", file=sys.stderr)
    return 1 if differences else 0


if __name__ == "__main__":
    sys.exit(main())
