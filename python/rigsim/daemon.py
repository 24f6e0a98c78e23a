"""Start rigsimd on a rig with ephemeral ports and a private pty dir; stop it and clean up."""

from __future__ import annotations

import json
import os
import secrets
import shutil
import signal
import subprocess
import tempfile
import time
from dataclasses import dataclass
from typing import Any, Final, Generator, Iterable, Sequence, Union, overload

from rigsim.control import ControlClient, Device, JsonObject, Pose

# A rig as Rigsim takes it: a rig JSON file's path, or the rig itself (written to a file for the
# daemon); None, where a rig is asked for, is the built-in default rig.
RigConfig = Union[str, "os.PathLike[str]", JsonObject]


class RigsimError(Exception):
    """rigsimd did not start, or not as asked; the message carries its log."""


@dataclass(frozen=True)
class Endpoint:
    """Where a client reaches one device."""

    name: str
    protocol: str   # "mcs", "apt"
    model: str
    tcp: str        # "127.0.0.1:40100"
    pty: str        # the pty's symlink path
    rfc2217: str = ""   # the RFC 2217 endpoint ("127.0.0.1:40101"; --rfc2217, "rfc2217_port"), or ""

    @property
    def url(self) -> str:
        """pyserial's URL for the TCP endpoint: serial.serial_for_url(endpoint.url)."""
        return "socket://" + self.tcp

    @property
    def rfc2217_url(self) -> str:
        """pyserial's URL for the RFC 2217 endpoint: serial.serial_for_url(endpoint.rfc2217_url)
        sets baud rate, data bits, parity, stop bits, RTS and DTR as on a serial port."""
        if not self.rfc2217:
            raise ValueError(f"device {self.name} has no RFC 2217 endpoint (rigsimd --rfc2217, or its rfc2217_port)")
        return "rfc2217://" + self.rfc2217

    @property
    def address(self) -> tuple[str, int]:
        """(host, port) of the TCP endpoint, for socket.create_connection()."""
        host, _, port = self.tcp.rpartition(":")
        return host.strip("[]"), int(port)


@dataclass(frozen=True)
class Noted:
    """One device's noted client mistakes (Rigsim.notes())."""

    device: str
    noted: int      # noted entries since start-up, reset or clear_log, kept or not
    entries: list[JsonObject]   # the noted wire log entries still kept, oldest first


def notes_text(found: Sequence[Noted]) -> str:
    """A readable list of Noted records: one line per noted entry with its notes."""
    total = sum(n.noted for n in found)
    lines = [f"rigsimd noted {total} client mistake(s):"]
    for n in found:
        for e in n.entries:
            decoded = e.get("decoded") or {}
            what = decoded.get("text") or decoded.get("name") or e.get("hex", "")
            lines.append(f"  {n.device} {e.get('time_ms', 0):.3f} ms {e.get('direction', '?')} {what}: "
                         + "; ".join(e.get("notes", [])))
        if n.noted > len(n.entries):
            lines.append(f"  {n.device}: {n.noted - len(n.entries)} more no longer in the wire log")
    return "\n".join(lines)


def find_rigsimd(explicit: str | None = None) -> str:
    """`explicit`, else $RIGSIMD, else rigsimd on PATH."""
    path = explicit or os.environ.get("RIGSIMD") or shutil.which("rigsimd")
    if not path:
        raise RigsimError("rigsimd not found: pass rigsimd=PATH, set RIGSIMD, or put it on PATH")
    # A relative path is taken from where we are now: tests may change directory later.
    return os.path.abspath(path) if os.sep in path else path


MODEM_LINES_SHIM: Final[str] = "librigsim_modemlines.so"


def modem_lines_shim(rigsimd: str | None = None) -> str:
    """The path of the RTS/DTR shim (librigsim_modemlines.so, docs/cli.md "Serial clients that
    toggle RTS/DTR"): $RIGSIM_MODEMLINES, else beside rigsimd (the build tree: scripts/run.sh
    builds both), else in ../lib beside it (cmake --install, the Debian layout). rigsimd is found
    as Rigsim finds it (`rigsimd`, $RIGSIMD, PATH). Raises RigsimError naming where it looked.

    A client that sets RTS or DTR on the pty (pyLabLib's and Thorlabs' APT port set-up) needs the
    shim preloaded in its own process, so it must be in LD_PRELOAD when that process starts:
    LD_PRELOAD=$(python3 -m rigsim.modem_lines) python3 -m pytest ..."""
    explicit = os.environ.get("RIGSIM_MODEMLINES")
    if explicit:
        if not os.path.isfile(explicit):
            raise RigsimError(f"RIGSIM_MODEMLINES names {explicit}, which is not a file")
        return os.path.abspath(explicit)
    daemon = find_rigsimd(rigsimd)
    daemon = shutil.which(daemon) or daemon
    here = os.path.dirname(os.path.realpath(daemon))
    candidates = [os.path.join(here, MODEM_LINES_SHIM), os.path.join(here, "..", "lib", MODEM_LINES_SHIM)]
    for candidate in candidates:
        if os.path.isfile(candidate):
            return os.path.normpath(candidate)
    raise RigsimError(f"{MODEM_LINES_SHIM} not found beside {daemon} (looked at "
                      f"{', '.join(os.path.normpath(c) for c in candidates)}): build it with scripts/run.sh "
                      "or `cmake --build BUILD --target rigsim_modemlines`, or set RIGSIM_MODEMLINES")


def modem_lines_preloaded() -> bool:
    """Whether the shim is loaded in this process (LD_PRELOAD took it when the process started)."""
    try:
        with open("/proc/self/maps", encoding="utf-8", errors="replace") as f:
            return any(line.rstrip().endswith("/" + MODEM_LINES_SHIM) for line in f)
    except OSError:
        return MODEM_LINES_SHIM in os.environ.get("LD_PRELOAD", "")


class Rigsim:
    """One rigsimd process on `rig`: a JSON file path, a dict (written to a file), or None for
    the built-in default rig. Extra command-line flags go in `args`.

    The control API takes a token: a fresh random one per daemon (`token`, passed to rigsimd in
    a file only this user can read), unless `args` give their own --control-token(-file)."""

    def __init__(self, rig: RigConfig | None = None, rigsimd: str | None = None, args: Iterable[str] = (),
                 start_timeout_s: float = 15.0) -> None:
        self.rigsimd = find_rigsimd(rigsimd)
        self.token: str | None = None
        self.rig = rig
        self.args = list(args)
        self.start_timeout_s = start_timeout_s
        self.process: subprocess.Popen[bytes] | None = None
        self.control: ControlClient | None = None   # set by start(), once the daemon listens
        self.endpoints: dict[str, Endpoint] = {}
        self.dir: str | None = None
        self.used: list[str] = []   # devices a test touched (endpoint/state/set/inject/log), in order
        self._log_copy = ""         # the daemon's log, kept when stop() removes its directory

    # ---- lifecycle ----

    def start(self) -> Rigsim:
        self.dir = tempfile.mkdtemp(prefix="rigsim-")
        cmd = [self.rigsimd, "--ephemeral-ports", "--pty-dir", os.path.join(self.dir, "pty"),
               "--endpoints-json", self._path("endpoints.json"), "--control", "127.0.0.1:0"]
        cmd += self._token_args()
        if isinstance(self.rig, dict):
            with open(self._path("rig.json"), "w") as f:
                json.dump(self.rig, f)
            cmd += ["--config", self._path("rig.json")]
        elif self.rig is not None:
            cmd += ["--config", os.fspath(self.rig)]
        with open(self._path("rigsimd.log"), "wb") as log:
            self.process = process = subprocess.Popen(cmd + self.args, stdout=subprocess.DEVNULL, stderr=log)
        try:
            self._wait_for_endpoints(process)
        except Exception:
            self.stop()
            raise
        return self

    def stop(self, timeout_s: float = 10.0) -> int | None:
        """SIGTERM, then SIGKILL after `timeout_s`; removes the pty dir. Returns the exit status."""
        status = None
        if self.process is not None:
            if self.process.poll() is None:
                self.process.send_signal(signal.SIGTERM)
                try:
                    self.process.wait(timeout_s)
                except subprocess.TimeoutExpired:
                    self.process.kill()
                    self.process.wait()
            status = self.process.returncode
            self.process = None
        if self.dir is not None:
            self._log_copy = self.daemon_log()
            shutil.rmtree(self.dir, ignore_errors=True)
            self.dir = None
        return status

    def __enter__(self) -> Rigsim:
        return self.start()

    def __exit__(self, *exc: object) -> None:
        self.stop()

    @overload
    def log(self, name: None = None, last: int | None = None) -> str: ...

    @overload
    def log(self, name: str, last: int | None = None) -> JsonObject: ...

    def log(self, name: str | None = None, last: int | None = None) -> str | JsonObject:
        """With a device `name`: its wire log (GET /api/devices/{name}/log[?last=N]).
        Without: the daemon's log (standard error) so far, as daemon_log()."""
        if name is None:
            return self.daemon_log()
        self._use(name)
        return self._client().log(name, last)

    def daemon_log(self) -> str:
        """The daemon's log (standard error) so far; kept after stop()."""
        if self.dir is None:
            return self._log_copy
        try:
            with open(self._path("rigsimd.log"), errors="replace") as f:
                return f.read()
        except FileNotFoundError:
            return ""

    # ---- what a test uses ----

    def endpoint(self, name: str) -> Endpoint:
        """The device `name`'s endpoints (pty path, TCP address, pyserial URL)."""
        try:
            endpoint = self.endpoints[name]
        except KeyError:
            raise KeyError(f"no device {name!r}; the rig has {sorted(self.endpoints)}") from None
        self._use(name)
        return endpoint

    def pause(self) -> JsonObject:
        return self._client().pause()

    def resume(self) -> JsonObject:
        return self._client().resume()

    def step(self, ms: int) -> JsonObject:
        return self._client().step(ms)

    def scale(self, factor: float) -> JsonObject:
        return self._client().scale(factor)

    def run_until_idle(self, max_ms: int = 600_000, check: bool = True, chunk_ms: int | None = None,
                       wait_for: tuple[str, str] | None = None, timeout_s: float = 5.0) -> JsonObject:
        """ControlClient.run_until_idle(): raises NotIdle when max_ms comes first, unless check=False."""
        return self._client().run_until_idle(max_ms, check=check, chunk_ms=chunk_ms, wait_for=wait_for,
                                           timeout_s=timeout_s)

    def wait_for_message(self, name: str, message: str, after: int | None = None, direction: str | None = "in",
                         timeout_s: float = 5.0) -> JsonObject:
        """ControlClient.wait_for_message(): the wire log entry of `message` sent to `name`."""
        self._use(name)
        return self._client().wait_for_message(name, message, after=after, direction=direction, timeout_s=timeout_s)

    def log_cursor(self, name: str) -> int:
        """ControlClient.log_cursor(): the seq of the newest entry of `name`'s wire log."""
        return self._client().log_cursor(name)

    def clock(self) -> JsonObject:
        return self._client().clock()

    def rig_state(self) -> JsonObject:
        """GET /api/rig: the devices, their endpoints and the clock."""
        return self._client().rig()

    def state(self, name: str | None = None) -> JsonObject:
        """GET /api/devices/{name}: the device's state; without a name, GET /api/rig."""
        if name is None:
            return self._client().rig()
        self._use(name)
        return self._client().state(name)

    def set(self, name: str, channel: int, **fields: Any) -> JsonObject:
        """PATCH /api/devices/{name}/channels/{channel}: position_si=, referenced=,
        limit_switch=, sensor=; returns the channel object after the change."""
        self._use(name)
        return self._client().set(name, channel, **fields)

    def device(self, name: str) -> Device:
        """A rigsim.control.Device handle on device `name` (state, set, trace, trigger)."""
        self._use(name)
        return self._client().device(name)

    def inject(self, device: str, kind: str, channel: int | None = None, **params: Any) -> int:
        """POST /api/faults: a fault `kind` on `device` (channel 0 unless given); returns its id."""
        self._use(device)
        return self._client().inject(device, kind, channel, **params)

    def clear_fault(self, fault_id: int) -> JsonObject:
        """DELETE /api/faults/{id}."""
        return self._client().clear_fault(fault_id)

    def clear_faults(self) -> JsonObject:
        """DELETE /api/faults: every fault."""
        return self._client().clear_faults()

    def faults(self) -> list[JsonObject]:
        """GET /api/faults: the list of fault objects."""
        return self._client().faults()

    def reset(self, keep_saved: bool = True) -> JsonObject:
        """POST /api/reset: every device back to power-up (saved settings kept unless
        keep_saved=False), faults removed, wire logs cleared."""
        return self._client().reset(keep_saved)

    def clear_log(self, name: str) -> JsonObject:
        """DELETE /api/devices/{name}/log."""
        return self._client().clear_log(name)

    def notes(self, devices: str | Iterable[str] | None = None) -> list[Noted]:
        """The client mistakes the daemon noted (docs/control-api.md, "The wire log"): a list of
        Noted(device, noted, entries), one per device with at least one, where `noted` counts the
        noted entries since start-up, the last reset or clear_log() (also those the log no longer
        keeps) and `entries` are the noted entries it still keeps. `devices`: a name or a list
        (None: every device of the rig)."""
        names = sorted(self.endpoints) if devices is None else (
            [devices] if isinstance(devices, str) else list(devices))
        found: list[Noted] = []
        for name in names:
            answer = self._client().log(name)
            entries = [e for e in answer.get("entries", []) if e.get("notes")]
            noted = answer.get("noted", len(entries))
            if noted or entries:
                found.append(Noted(name, noted, entries))
        return found

    def assert_no_notes(self, devices: str | Iterable[str] | None = None) -> None:
        """Raise AssertionError listing every noted client mistake (notes()), if there is one:
        a test's client sent something the real unit would reject, ignore or take only by luck."""
        found = self.notes(devices)
        if found:
            raise AssertionError(notes_text(found))

    def events(self, device: str | Iterable[str] | None = None, timeout: float | None = None,
               type: str | Iterable[str] | None = None) -> Generator[JsonObject, None, None]:
        """GET /api/events[?device=&type=]: an iterator of event dicts; ends after `timeout` s
        without one."""
        return self._client().events(device, timeout, type)

    def frames(self) -> JsonObject:
        """GET /api/frames: every frame and tool point of the rig's kinematics, and the contacts."""
        return self._client().frames()

    def pose(self, name: str) -> Pose:
        """GET /api/frames/{name} as a rigsim.control.Pose: position_mm, quaternion (w, x, y, z)
        and rpy_deg in the world, and the same relative to its parent (pose.parent_relative)."""
        return self._client().pose(name)

    # ---- internals ----

    def _use(self, name: str) -> None:
        if name not in self.used:
            self.used.append(name)

    def _client(self) -> ControlClient:
        """The control API's client, once start() found it."""
        if self.control is None:
            raise RigsimError("rigsimd is not started: call start(), or use Rigsim as a context manager")
        return self.control

    def _path(self, name: str) -> str:
        if self.dir is None:
            raise RigsimError("rigsimd is not started: it has no directory yet")
        return os.path.join(self.dir, name)

    def _token_args(self) -> list[str]:
        """--control-token-file with a fresh token, unless the caller's args give one."""
        args = self.args
        for i, arg in enumerate(args):
            name, _, inline = arg.partition("=")
            if name in ("--control-token", "--control-token-file"):
                value = inline if inline else (args[i + 1] if i + 1 < len(args) else "")
                if name == "--control-token":
                    self.token = value
                else:
                    with open(value) as f:
                        self.token = f.readline().strip()
                return []
        # Hex, not base64url: a token starting with "-" would read as a flag when passed on to
        # a command line (`rigsimctl --token -x...`: one run in 64 failed so).
        self.token = secrets.token_hex(32)
        path = self._path("control-token")
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        with os.fdopen(fd, "w") as f:
            f.write(self.token + "\n")
        return ["--control-token-file", path]

    def _wait_for_endpoints(self, process: subprocess.Popen[bytes]) -> None:
        deadline = time.monotonic() + self.start_timeout_s
        path = self._path("endpoints.json")
        while time.monotonic() < deadline:
            if process.poll() is not None:
                raise RigsimError(f"rigsimd exited with status {process.returncode}:\n{self.log()}")
            try:
                with open(path) as f:
                    doc = json.load(f)
                break
            except (FileNotFoundError, ValueError):
                time.sleep(0.02)
        else:
            raise RigsimError(f"rigsimd wrote no endpoints within {self.start_timeout_s} s:\n{self.log()}")
        if "control" not in doc:
            raise RigsimError("the endpoints file names no control API: is this rigsimd older than --control?")
        self.control = ControlClient(doc["control"], token=self.token)
        self.endpoints = {d["name"]: Endpoint(d["name"], d["protocol"], d["model"], d["tcp"], d["pty"],
                                              d.get("rfc2217", ""))
                          for d in doc["devices"]}
