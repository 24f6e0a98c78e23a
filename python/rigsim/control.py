"""A client of rigsimd's HTTP control API (docs/control-api.md), standard library only."""

from __future__ import annotations

import http.client
import json
import os
import queue
import socket
import threading
import time
import urllib.error
import urllib.parse
import urllib.request
from typing import Any, Final, Generator, Iterable, Mapping, NamedTuple

# A decoded JSON object, as every route answers one: mypy sees its values as Any (the shape of
# each answer is docs/control-api.md's, not something the client checks).
JsonObject = dict[str, Any]


class ControlError(Exception):
    """The control API answered with an error: `status` (4xx) and its `message`."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(f"{status}: {message}")
        self.status = status
        self.message = message


class NotIdle(Exception):
    """run_until_idle() reached its max_ms while something still moved or settled; `clock` is
    the daemon's answer (with "reached_ms" and "idle": false)."""

    def __init__(self, clock: JsonObject, max_ms: int) -> None:
        super().__init__(f"still busy after {max_ms} ms of clock time (now_ms {clock.get('now_ms')}): "
                         "something still moves, settles or runs; raise max_ms, or pass check=False")
        self.clock = clock


def _message_matches(entry: JsonObject, message: str, direction: str | None) -> bool:
    """Whether wire log `entry` is `message` in `direction`: an APT name with or without its
    MGMSG_ prefix, or an MCS command (MPA) or its name."""
    if direction is not None and entry.get("direction") != direction:
        return False
    decoded = entry.get("decoded") or {}
    names = {decoded.get("name"), decoded.get("command")}
    return message in names or "MGMSG_" + message in names


def _quote(name: object) -> str:
    return urllib.parse.quote(str(name), safe="")


def _error_message(text: str) -> str:
    try:
        message = json.loads(text).get("error", text)
    except (ValueError, AttributeError):
        message = text
    return str(message)


# Where the built-in default rig's control API listens (config/default.json "control"): what
# ControlClient() and rigsimctl reach when given no address.
DEFAULT_CONTROL: Final[str] = "127.0.0.1:40200"


# The control API is reached directly, never through the http_proxy/HTTPS_PROXY of the
# environment (a lab's proxy cannot reach the daemon on this machine's loopback, and the daemon
# refuses a Host header it does not serve).
_DIRECT: Final[urllib.request.OpenerDirector] = urllib.request.build_opener(urllib.request.ProxyHandler({}))


class NotControlApi(OSError):
    """The address answered, but not as rigsimd's control API does (a device's TCP port, another
    server): the message says so, in one line. An OSError, as the connection's other failures."""


class NoControlAnswer(NotControlApi, TimeoutError):
    """No HTTP answer within the client's timeout: an APT device's port (which ignores HTTP), or a
    daemon too busy to answer. A TimeoutError too, as before the message named the port."""


def control_url(address: str | None = None) -> str:
    """The control API's base URL from `address`: "http://HOST:PORT", or "HOST:PORT" and
    "[IPv6]:PORT" as rigsimd --control takes them (http:// is added); None: the default rig's
    (DEFAULT_CONTROL)."""
    text = (address or DEFAULT_CONTROL).strip()
    if "://" not in text:
        text = "http://" + text
    return text.rstrip("/")


def _address_of(url: str) -> str:
    return urllib.parse.urlsplit(url).netloc or url


def _answer_text(exc: BaseException) -> str:
    """What a non-HTTP peer sent, as http.client saw it (BadStatusLine's line), shortened."""
    seen: object = exc.args[0] if exc.args else ""
    if isinstance(seen, bytes):
        seen = seen.decode("latin-1")
    line = str(seen).strip()
    return line[:40] + ("..." if len(line) > 40 else "")


def _not_control_api(url: str, exc: BaseException, timeout_s: float) -> NotControlApi:
    """A NotControlApi that says what `url` did instead of answering HTTP."""
    where = _address_of(url)
    hint = ("the control API's address is the 'control:' line rigsimd prints, the \"control\" key "
            f"of --endpoints-json, or {DEFAULT_CONTROL} for the default rig")
    if isinstance(exc, (TimeoutError, socket.timeout)):
        return NoControlAnswer(f"no HTTP answer from {where} within {timeout_s:g} s: is it a device's port "
                               f"(an APT device ignores HTTP) or a busy daemon? {hint}")
    if isinstance(exc, http.client.RemoteDisconnected):
        return NotControlApi(f"{where} closed the connection without an HTTP answer: is it a device's "
                             f"port? {hint}")
    seen = _answer_text(exc)
    kind = " (a SmarAct MCS answer)" if seen.startswith(":") else ""
    return NotControlApi(f"{where} answered {seen!r}{kind}, not HTTP: that is a device's port, not the "
                         f"control API; {hint}")


class TraceSample(NamedTuple):
    """One sample of a piezo channel's trace (docs/control-api.md#traces): the clock tick, the
    output as GET_OUTPUTVOLTS codes it, the output in volts, the actuator's physical extension in um, and
    the LUT index being output (None when no LUT runs)."""

    tick: int
    output_code: int
    output_v: float
    position_um: float
    lut_index: int | None


TRACE_PAGE: Final[int] = 16384   # the most samples one trace request answers (the ring's capacity)


class Placement(NamedTuple):
    """Where a frame is (docs/control-api.md#frames-get-apiframes): its origin in mm,
    its orientation as a unit quaternion (w, x, y, z) with w >= 0, and as roll, pitch, yaw in degrees
    (R = Rz(yaw) Ry(pitch) Rx(roll)). Each a tuple of floats."""

    position_mm: tuple[float, ...]
    quaternion: tuple[float, ...]
    rpy_deg: tuple[float, ...]


def _placement(doc: JsonObject) -> Placement:
    return Placement(tuple(doc["position_mm"]), tuple(doc["quaternion"]), tuple(doc["rpy_deg"]))


class Pose(NamedTuple):
    """One frame or tool point of the rig's kinematics, as GET /api/frames/{name} gives it:
    `world` and `parent_relative` are Placements; `joint` is None for a fixed frame, else a
    dict {type, device, channel, position} (position in mm or degrees). position_mm,
    quaternion and rpy_deg are the world placement's."""

    name: str
    parent: str | None
    tool: bool
    joint: JsonObject | None
    world: Placement
    parent_relative: Placement

    @classmethod
    def from_json(cls, doc: JsonObject) -> Pose:
        return cls(doc["name"], doc.get("parent"), bool(doc.get("tool")), doc.get("joint"),
                   _placement(doc["world"]), _placement(doc["parent_relative"]))

    @property
    def position_mm(self) -> tuple[float, ...]:
        return self.world.position_mm

    @property
    def quaternion(self) -> tuple[float, ...]:
        return self.world.quaternion

    @property
    def rpy_deg(self) -> tuple[float, ...]:
        return self.world.rpy_deg


class ControlClient:
    """The routes of the control API at `url`: "http://127.0.0.1:PORT", or "HOST:PORT" as
    rigsimd --control takes it; None: the default rig's (DEFAULT_CONTROL, 127.0.0.1:40200).

    `token`: the daemon's --control-token, sent as "Authorization: Bearer <token>"; None reads
    the environment variable RIGSIM_CONTROL_TOKEN (unset or empty: no token).

    An address that answers, but not with HTTP (a device's TCP port), raises NotControlApi."""

    def __init__(self, url: str | None = None, timeout_s: float = 10.0, token: str | None = None,
                 run_timeout_s: float = 120.0) -> None:
        self.url = control_url(url)
        self.timeout_s = timeout_s
        # A request that runs the clock (step, run_until_idle) answers once the clock time has
        # run: its wall time grows with the simulation's work (seconds under a sanitizer).
        self.run_timeout_s = max(run_timeout_s, timeout_s)
        self.token = token if token is not None else os.environ.get("RIGSIM_CONTROL_TOKEN") or None

    def _headers(self, extra: Mapping[str, str] | None = None) -> dict[str, str]:
        headers = dict(extra or {})
        if self.token:
            headers["Authorization"] = "Bearer " + self.token
        return headers

    def request(self, method: str, path: str, body: object = None, timeout_s: float | None = None) -> Any:
        """One request; returns the decoded JSON answer or raises ControlError. `timeout_s`
        (default: the client's) bounds the wait for the answer."""
        timeout = self.timeout_s if timeout_s is None else timeout_s
        data = None if body is None else json.dumps(body).encode()
        headers = self._headers({"Content-Type": "application/json"} if data is not None else None)
        req = urllib.request.Request(self.url + path, data=data, method=method, headers=headers)
        try:
            with _DIRECT.open(req, timeout=timeout) as answer:
                return json.loads(answer.read() or b"null")
        except urllib.error.HTTPError as e:
            text = e.read().decode(errors="replace")
            raise ControlError(e.code, _error_message(text)) from None
        except (http.client.HTTPException, TimeoutError, socket.timeout) as e:
            raise _not_control_api(self.url, e, timeout) from None

    def _object(self, method: str, path: str, body: object = None, timeout_s: float | None = None) -> JsonObject:
        """request() for the routes, each of which answers a JSON object."""
        answer: JsonObject = self.request(method, path, body, timeout_s)
        return answer

    # ---- rig and clock ----

    def rig(self) -> JsonObject:
        """GET /api/rig: the devices and the clock."""
        return self._object("GET", "/api/rig")

    def clock(self) -> JsonObject:
        """GET /api/clock."""
        return self._object("GET", "/api/clock")

    def pause(self) -> JsonObject:
        """Stop the clock at the current tick."""
        return self._object("POST", "/api/clock", {"pause": True})

    def resume(self) -> JsonObject:
        """Run the clock again from the current tick."""
        return self._object("POST", "/api/clock", {"resume": True})

    def step(self, ms: int) -> JsonObject:
        """Advance the clock `ms` milliseconds now (paused or running)."""
        return self._object("POST", "/api/clock", {"step_ms": ms}, self.run_timeout_s)

    def scale(self, factor: float) -> JsonObject:
        """Run the clock `factor` times faster than wall time from now on."""
        return self._object("POST", "/api/clock", {"scale": factor})

    def run_until_idle(self, max_ms: int, check: bool = True, chunk_ms: int | None = None,
                       wait_for: tuple[str, str] | None = None, timeout_s: float = 5.0) -> JsonObject:
        """Advance as fast as the CPU allows until nothing moves, at most `max_ms` of clock time.

        Idle means the world and every device: no motion, settling, calibration, move delay or
        LUT run left. When `max_ms` comes first the answer has "idle": false and this raises
        NotIdle, unless `check` is False.

        For drivers with a thread of their own: `chunk_ms` runs the clock in pieces of that many
        milliseconds; after each piece that left the rig busy, `wait_for=(device, message)` waits
        (up to `timeout_s` of wall time) until the device received that message after the piece
        ended (a driver's keep-alive or status acknowledgement), so the driver keeps up."""
        if chunk_ms is None:
            if wait_for is not None:
                raise ValueError("wait_for needs chunk_ms")
            answer = self._run_until_idle(max_ms)
        else:
            answer = self._run_in_chunks(max_ms, int(chunk_ms), wait_for, timeout_s)
        if check and answer.get("idle") is False:
            raise NotIdle(answer, max_ms)
        return answer

    def _run_until_idle(self, max_ms: int) -> JsonObject:
        return self._object("POST", "/api/clock", {"run_until_idle": True, "max_ms": int(max_ms)},
                            self.run_timeout_s)

    def _run_in_chunks(self, max_ms: int, chunk_ms: int, wait_for: tuple[str, str] | None,
                       timeout_s: float) -> JsonObject:
        if chunk_ms < 1:
            raise ValueError(f"chunk_ms must be at least 1, got {chunk_ms}")
        left = int(max_ms)
        while True:
            answer = self._run_until_idle(min(chunk_ms, left))
            left -= min(chunk_ms, left)
            if answer.get("idle") is not False or left <= 0:
                return answer
            if wait_for:
                # After the piece: the message must come once the piece's clock time has run (an
                # acknowledgement sent during it does not answer what the piece sent after it).
                cursor = self.log_cursor(wait_for[0])
                self.wait_for_message(wait_for[0], wait_for[1], after=cursor, timeout_s=timeout_s)

    def log_cursor(self, name: str) -> int:
        """The seq of the newest entry of `name`'s wire log (0 when empty): pass it as
        wait_for_message(after=...) to wait for a message that comes after this point."""
        entries = self.log(name, last=1).get("entries", [])
        return int(entries[-1]["seq"]) if entries else 0

    def wait_for_message(self, name: str, message: str, after: int | None = None, direction: str | None = "in",
                         timeout_s: float = 5.0, poll_s: float = 0.005) -> JsonObject:
        """Wait (wall time, the clock stands or runs as it does) until device `name`'s wire log
        holds `message` after seq `after` (None: anywhere in the log), and return that entry.

        `message` is an APT name (MOT_MOVE_ABSOLUTE, with or without MGMSG_) or an MCS command
        (MPA); `direction` "in" (from a client, the default), "out", or None for either. This is
        how a test waits until a driver's own thread has sent its command before it runs the
        clock. Raises TimeoutError after `timeout_s`."""
        deadline = time.monotonic() + timeout_s
        while True:
            entries: list[JsonObject] = self.log(name).get("entries", [])
            if after is not None and entries and entries[-1]["seq"] < after:
                after = 0   # the log was emptied (a reset) since the cursor was taken
            for entry in entries:
                if (after is None or entry["seq"] > after) and _message_matches(entry, message, direction):
                    return entry
            if time.monotonic() >= deadline:
                seen = [(e.get("decoded") or {}).get("name") for e in entries[-5:]]
                raise TimeoutError(f"{name} received no {message} within {timeout_s} s (last entries: {seen})")
            time.sleep(poll_s)

    # ---- devices ----

    def state(self, name: str) -> JsonObject:
        """GET /api/devices/{name}: the device's state, channel by channel."""
        return self._object("GET", f"/api/devices/{_quote(name)}")

    def set(self, name: str, channel: int, **fields: Any) -> JsonObject:
        """PATCH /api/devices/{name}/channels/{channel} with `fields` (position_si=, referenced=,
        limit_switch=, sensor=); returns the channel object after the change."""
        return self._object("PATCH", f"/api/devices/{_quote(name)}/channels/{int(channel)}", fields)

    def trace_page(self, name: str, channel: int, since: int | None = None,
                   max_samples: int | None = None) -> JsonObject:
        """GET /api/devices/{name}/channels/{channel}/trace[?from=&max=]: one answer as the route
        gives it (tick_hz, capacity, kept, oldest_tick, next_from, samples)."""
        query = []
        if since is not None:
            query.append(f"from={int(since)}")
        if max_samples is not None:
            query.append(f"max={int(max_samples)}")
        path = f"/api/devices/{_quote(name)}/channels/{int(channel)}/trace"
        return self._object("GET", path + ("?" + "&".join(query) if query else ""))

    def trace(self, name: str, channel: int, since: int | None = None) -> list[TraceSample]:
        """Every sample the channel's trace keeps from tick `since` on (all when None), oldest
        first, as TraceSample tuples; pages through the route until it has them all."""
        samples: list[TraceSample] = []
        start = 0 if since is None else int(since)
        while True:
            page = self.trace_page(name, channel, start, TRACE_PAGE)
            samples.extend(TraceSample(*s) for s in page["samples"])
            if len(page["samples"]) < TRACE_PAGE:
                return samples
            start = page["next_from"]

    def trigger(self, name: str, channel: int) -> JsonObject:
        """PATCH trig_in "pulse": a rising and a falling edge on the channel's TRIG IN in one
        tick (a BPC30x bay's LUT input trigger, a solenoid's triggered mode); returns the channel."""
        return self.set(name, channel, trig_in="pulse")

    def device(self, name: str) -> Device:
        """A Device handle on `name`."""
        return Device(self, name)

    def log(self, name: str, last: int | None = None) -> JsonObject:
        """GET /api/devices/{name}/log[?last=N]: the device's wire log."""
        query = "" if last is None else f"?last={int(last)}"
        return self._object("GET", f"/api/devices/{_quote(name)}/log{query}")

    def clear_log(self, name: str) -> JsonObject:
        """DELETE /api/devices/{name}/log."""
        return self._object("DELETE", f"/api/devices/{_quote(name)}/log")

    # ---- frames ----

    def frames(self) -> JsonObject:
        """GET /api/frames: {"frames": [...], "tools": [...], "collisions": [...]} as the route
        gives it (empty lists when the rig has no kinematics)."""
        return self._object("GET", "/api/frames")

    def frame(self, name: str) -> JsonObject:
        """GET /api/frames/{name}: one frame or tool point as the route gives it (404: none)."""
        return self._object("GET", f"/api/frames/{_quote(name)}")

    def pose(self, name: str) -> Pose:
        """The frame or tool point `name` as a Pose (world and parent-relative placements)."""
        return Pose.from_json(self.frame(name))

    # ---- faults ----

    def inject(self, device: str, kind: str, channel: int | None = None, **params: Any) -> int:
        """POST /api/faults; returns the fault's id."""
        return int(self.add_fault(device, kind, channel, **params)["id"])

    def add_fault(self, device: str, kind: str, channel: int | None = None, **params: Any) -> JsonObject:
        """POST /api/faults; returns the whole fault object (id, active, since_ms, ...)."""
        body: JsonObject = {"device": device, "kind": kind}
        if channel is not None:
            body["channel"] = int(channel)
        body.update(params)
        return self._object("POST", "/api/faults", body)

    def faults(self) -> list[JsonObject]:
        """GET /api/faults: the list of fault objects."""
        faults: list[JsonObject] = self._object("GET", "/api/faults")["faults"]
        return faults

    def clear_fault(self, fault_id: int) -> JsonObject:
        """DELETE /api/faults/{id}."""
        return self._object("DELETE", f"/api/faults/{int(fault_id)}")

    def clear_faults(self) -> JsonObject:
        """DELETE /api/faults: every fault; returns {"removed": [ids]}."""
        return self._object("DELETE", "/api/faults")

    # ---- reset and events ----

    def reset(self, keep_saved: bool = True) -> JsonObject:
        """POST /api/reset: every device back to power-up, faults removed, wire logs cleared."""
        return self._object("POST", "/api/reset", {} if keep_saved else {"keep_saved": False})

    def events(self, device: str | Iterable[str] | None = None, timeout: float | None = None,
               type: str | Iterable[str] | None = None) -> Generator[JsonObject, None, None]:
        """GET /api/events: an iterator of the events as dicts (the `data` object, with "type"
        and "seq" filled from the `event:` and `id:` lines when the data lacks them).

        `device` and `type` are each a name or a list of names (the server filters: type="frames"
        gives only the frames events). The iterator ends when no event arrives for `timeout`
        seconds (None: it waits for ever); close() it (or leave the for loop) to drop the
        connection. Opening raises ControlError on an error answer."""
        query = []
        for key, value in (("device", device), ("type", type)):
            if value is not None:
                names = [value] if isinstance(value, str) else list(value)
                query.append(key + "=" + ",".join(_quote(n) for n in names))
        path = "/api/events" + ("?" + "&".join(query) if query else "")
        req = urllib.request.Request(self.url + path, headers=self._headers({"Accept": "text/event-stream"}))
        try:
            answer = _DIRECT.open(req, timeout=self.timeout_s)
        except urllib.error.HTTPError as e:
            raise ControlError(e.code, _error_message(e.read().decode(errors="replace"))) from None
        except (http.client.HTTPException, TimeoutError, socket.timeout) as e:
            raise _not_control_api(self.url, e, self.timeout_s) from None
        return _event_iterator(answer, timeout)


def _read_events(answer: http.client.HTTPResponse, events: queue.Queue[JsonObject | None]) -> None:
    """The reader thread: parses the SSE stream into `events` until it ends or is closed (then
    puts None)."""
    fields: dict[str, str] = {}
    data: list[str] = []
    try:
        # The stream is read without a timeout: an idle stream is normal; close() ends it.
        sock = getattr(getattr(getattr(answer, "fp", None), "raw", None), "_sock", None)
        if sock is not None:
            sock.settimeout(None)
        for raw in answer:
            line = raw.decode("utf-8", errors="replace").rstrip("\r\n")
            if line == "":
                if data:
                    events.put(_event(fields, "\n".join(data)))
                fields, data = {}, []
            elif line.startswith(":"):
                continue   # an SSE comment (keep-alive)
            else:
                key, _, value = line.partition(":")
                value = value[1:] if value.startswith(" ") else value
                if key == "data":
                    data.append(value)
                else:
                    fields[key] = value
    except (OSError, ValueError, AttributeError):
        pass   # closed under us, or the server went away
    finally:
        events.put(None)


def _event(fields: Mapping[str, str], text: str) -> JsonObject:
    try:
        decoded: Any = json.loads(text)
    except ValueError:
        decoded = {"data": text}
    event: JsonObject = decoded if isinstance(decoded, dict) else {"data": decoded}
    if "event" in fields:
        event.setdefault("type", fields["event"])
    if "id" in fields:
        seq = fields["id"]
        event.setdefault("seq", int(seq) if seq.isdigit() else seq)
    return event


def _event_iterator(answer: http.client.HTTPResponse,
                    timeout: float | None) -> Generator[JsonObject, None, None]:
    events: queue.Queue[JsonObject | None] = queue.Queue()
    reader = threading.Thread(target=_read_events, args=(answer, events), daemon=True)
    reader.start()
    try:
        while True:
            try:
                event = events.get(timeout=timeout)
            except queue.Empty:
                return
            if event is None:   # the stream ended
                return
            yield event
    finally:
        _close_stream(answer)


def _close_stream(answer: http.client.HTTPResponse) -> None:
    """Unblock the reader thread: shut the socket down, then close the answer."""
    sock = getattr(getattr(getattr(answer, "fp", None), "raw", None), "_sock", None)
    if sock is not None:
        try:
            sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
    try:
        answer.close()
    except Exception:   # closing a response another thread reads may raise anything
        pass


class Device:
    """One device of the rig through a ControlClient: its state, its channels' set-up, traces and
    triggers, without repeating its name."""

    def __init__(self, control: ControlClient, name: str) -> None:
        self.control = control
        self.name = name

    def state(self) -> JsonObject:
        """GET /api/devices/{name}."""
        return self.control.state(self.name)

    def channel(self, channel: int) -> JsonObject:
        """GET /api/devices/{name}/channels/{channel}: one channel object."""
        return self.control._object("GET", f"/api/devices/{_quote(self.name)}/channels/{int(channel)}")

    def set(self, channel: int, **fields: Any) -> JsonObject:
        """PATCH the channel with `fields`; returns the channel object after the change."""
        return self.control.set(self.name, channel, **fields)

    def trace(self, channel: int, since: int | None = None) -> list[TraceSample]:
        """The channel's output trace from tick `since` on (all it keeps when None): a list of
        TraceSample(tick, output_code, output_v, position_um, lut_index), oldest first. Only
        piezo channels have one (ControlError 404 otherwise)."""
        return self.control.trace(self.name, channel, since)

    def trigger(self, channel: int) -> JsonObject:
        """A pulse on the channel's TRIG IN (PATCH trig_in "pulse"): starts an armed BPC30x LUT
        (OUTPUTLUTPARAMS input trigger, p. 108) or a primed solenoid's cycles; ControlError 400 on
        a unit without a trigger input (TPZ001, KPZ101)."""
        return self.control.trigger(self.name, channel)
