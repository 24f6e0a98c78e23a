"""pytest plugin: the `rigsim` fixture factory, its session-scoped variant `rigsim_session`, and
`rigsim_rig`, the session's daemon on the rig the command line or the ini file names.

    def test_home(rigsim):
        rig = rigsim("my-rig.json")          # or a dict, or no argument for the default rig
        rig.pause()
        ...

    def test_sample_follows(rigsim):
        rig = rigsim("my-rig.json")         # a rig with "kinematics"
        ...                                  # clients move the stages
        assert rig.pose("sample").position_mm == pytest.approx((10, 0, 90), abs=1e-6)

    def test_fast(rigsim_session):
        rig = rigsim_session("my-rig.json")  # one daemon per rig for the whole session,
        ...                                  # reset() before each test that asks for it

    def test_ready(rigsim_rig):               # --rigsim-rig=FILE or the ini key rigsim_rig
        port = rigsim_rig.endpoint("kdc101").address
        ...

Every daemon `rigsim` started is stopped (its ptys removed) when the test ends; `rigsim_session`
daemons when the session ends. When a test fails, in its setup, body or teardown, the report
gets each daemon's log (for a session daemon: the part written during the test) and the wire log
of every device the test used (called endpoint(), state(), set(), inject() or log() on).

Strict mode (--rigsim-strict, or the ini key `rigsim_strict = true`; per test
@pytest.mark.rigsim_strict or @pytest.mark.rigsim_strict(False)) fails a test whose clients
made mistakes the daemon noted in a wire log (Rigsim.assert_no_notes() does the same on demand).

rigsimd is found by --rigsimd=PATH (relative to the directory pytest was started in), the
`rigsimd` ini key (relative to the ini file's directory, pytest's rootdir), $RIGSIMD, or PATH,
in that order. Give the option with `=`: pytest finds the project's ini file before it knows
the plugin's options, and reads a separate `--rigsimd PATH` as a path to test, which can move
the rootdir away from the project.

Enable it with `-p rigsim.pytest_plugin` or `pytest_plugins = ["rigsim.pytest_plugin"]` in a
conftest.py; an installed package (pip install ./python) registers it by its pytest11 entry
point of the same name, so pytest loads it without either (and both still work).
"""

from __future__ import annotations

import json
import os
from typing import Any, Final, Generator, Iterable, Iterator, Protocol

import pytest

from rigsim.control import ControlClient, ControlError, JsonObject, NotControlApi
from rigsim.daemon import RigConfig, Rigsim, notes_text

# (daemon, offset of its log when the test got it) for every daemon a test used.
_DAEMONS = pytest.StashKey[list[tuple[Rigsim, int]]]()
# Set once the logs were attached to one of the test's reports (setup, call or teardown).
_ATTACHED = pytest.StashKey[bool]()

WIRE_LOG_LAST: Final[int] = 200   # entries of each device's wire log attached to a failed test's report

_STRICT_HELP: Final[str] = ("fail a test whose clients made mistakes the daemon noted in a wire log "
                "(Rigsim.assert_no_notes(); per test: @pytest.mark.rigsim_strict(False))")


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("rigsim", "rigsim (rigsimd for tests)")
    group.addoption("--rigsimd", default=None, metavar="PATH",
                    help="path of the rigsimd binary for the rigsim fixtures; write it as "
                         "--rigsimd=PATH (a separate PATH is taken for a test path when pytest "
                         "looks for its ini file)")
    parser.addini("rigsimd", default=None,
                  help="path of the rigsimd binary for the rigsim fixtures (relative: to the ini file's directory)")
    group.addoption("--rigsim-rig", default=None, metavar="FILE",
                    help="the rig JSON of the rigsim_rig fixture (default: the ini key rigsim_rig, "
                         "else the built-in default rig); write it as --rigsim-rig=FILE")
    parser.addini("rigsim_rig", default=None,
                  help="the rig JSON of the rigsim_rig fixture (relative: to the ini file's directory)")
    group.addoption("--rigsim-strict", action="store_true", default=None, help=_STRICT_HELP)
    parser.addini("rigsim_strict", type="bool", default=False, help=_STRICT_HELP)


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers", "rigsim_strict(enabled=True): fail (or with False, do not fail) this test when "
                   "the daemon noted a client mistake, whatever --rigsim-strict and rigsim_strict say")


# ---- where things are ----

def _ini_dir(config: pytest.Config) -> str:
    """Where relative paths of ini keys are taken from: the ini file's directory (pytest's
    rootdir), else the rootdir."""
    inipath = getattr(config, "inipath", None)
    return str(inipath.parent) if inipath else str(config.rootpath)


def _invocation_dir(config: pytest.Config) -> str:
    return str(config.invocation_params.dir)


def _resolve(path: str, base: str) -> str:
    path = os.path.expanduser(path)
    return path if os.path.isabs(path) else os.path.normpath(os.path.join(base, path))


def _rigsimd_path(config: pytest.Config) -> str | None:
    """--rigsimd (from the invocation directory), else the ini key (from the ini file's
    directory), else None: Rigsim then tries $RIGSIMD and PATH. A bare name (no '/') is looked
    up on PATH as given."""
    option = config.getoption("--rigsimd")
    if option:
        return _resolve(option, _invocation_dir(config)) if os.sep in option else option
    ini = config.getini("rigsimd")
    if ini:
        return _resolve(ini, _ini_dir(config)) if os.sep in ini else ini
    return None


def _rig_path(config: pytest.Config) -> str | None:
    """The rigsim_rig fixture's rig: --rigsim-rig, else the ini key rigsim_rig, else None (the
    built-in default rig)."""
    option = config.getoption("--rigsim-rig")
    if option:
        return _resolve(option, _invocation_dir(config))
    ini = config.getini("rigsim_rig")
    if ini:
        return _resolve(ini, _ini_dir(config))
    return None


def _strict(item: pytest.Item) -> bool:
    marker = item.get_closest_marker("rigsim_strict")
    if marker is not None:
        return bool(marker.args[0]) if marker.args else bool(marker.kwargs.get("enabled", True))
    if item.config.getoption("--rigsim-strict"):
        return True
    return bool(item.config.getini("rigsim_strict"))


def _used_by(item: pytest.Item) -> list[tuple[Rigsim, int]]:
    return item.stash.setdefault(_DAEMONS, [])


# ---- the fixtures ----

class RigsimFactory(Protocol):
    """What the `rigsim` and `rigsim_session` fixtures give a test: called with (rig=None,
    args=()), it returns a Rigsim. A typed test names it: def test_home(rigsim: RigsimFactory)."""

    def __call__(self, rig: RigConfig | None = None, args: Iterable[str] = ()) -> Rigsim: ...


@pytest.fixture
def rigsim(request: pytest.FixtureRequest) -> Iterator[RigsimFactory]:
    """Factory: rigsim(rig=None, args=()) starts rigsimd on `rig` and returns a Rigsim; stopped
    when the test ends."""
    started: list[Rigsim] = []
    used = _used_by(request.node)

    def start(rig: RigConfig | None = None, args: Iterable[str] = ()) -> Rigsim:
        daemon = Rigsim(rig, rigsimd=_rigsimd_path(request.config), args=args)
        started.append(daemon)
        used.append((daemon, 0))
        return daemon.start()

    yield start
    for daemon in started:
        daemon.stop()


# A session daemon's key: its rig as JSON text, and its extra flags.
_DaemonKey = tuple[str, tuple[str, ...]]


class _SessionDaemons:
    """The daemons of the session, one per (rig, args), and the clock each started with."""

    def __init__(self, rigsimd: str | None) -> None:
        self.rigsimd = rigsimd
        self.daemons: dict[_DaemonKey, tuple[Rigsim, JsonObject]] = {}

    @staticmethod
    def key(rig: RigConfig | None, args: Iterable[str]) -> _DaemonKey:
        return (json.dumps(rig, sort_keys=True, default=str), tuple(args))

    def get(self, rig: RigConfig | None, args: Iterable[str]) -> Rigsim:
        key = self.key(rig, args)
        entry = self.daemons.get(key)
        if entry is not None and entry[0].process is not None and entry[0].process.poll() is None:
            daemon, clock = entry
            self._reset(daemon, clock, rig, args, key)
            return self.daemons[key][0]
        if entry is not None:
            entry[0].stop()
        daemon = Rigsim(rig, rigsimd=self.rigsimd, args=args).start()
        self.daemons[key] = (daemon, daemon.clock())
        return daemon

    def _reset(self, daemon: Rigsim, clock: JsonObject, rig: RigConfig | None, args: Iterable[str],
               key: _DaemonKey) -> None:
        """POST /api/reset, and the clock back to how it started (running or paused, scale)."""
        try:
            daemon.reset()
        except ControlError as e:
            if e.status != 404:
                raise
            # A daemon without /api/reset: a fresh one is the only clean state.
            daemon.stop()
            fresh = Rigsim(rig, rigsimd=self.rigsimd, args=args).start()
            self.daemons[key] = (fresh, fresh.clock())
            return
        if daemon.clock()["time_scale"] != clock["time_scale"]:
            daemon.scale(clock["time_scale"])
        if clock["paused"]:
            daemon.pause()
        else:
            daemon.resume()
        daemon.used = []

    def stop_all(self) -> None:
        for daemon, _ in self.daemons.values():
            daemon.stop()


@pytest.fixture(scope="session")
def _rigsim_session_daemons(pytestconfig: pytest.Config) -> Iterator[_SessionDaemons]:
    daemons = _SessionDaemons(_rigsimd_path(pytestconfig))
    yield daemons
    daemons.stop_all()


@pytest.fixture
def rigsim_session(request: pytest.FixtureRequest, _rigsim_session_daemons: _SessionDaemons) -> RigsimFactory:
    """Factory: rigsim_session(rig=None, args=()) returns the session's daemon on `rig` (started
    on first use, stopped at the end of the session), reset() and its clock restored first."""
    used = _used_by(request.node)
    handed: dict[_DaemonKey, Rigsim] = {}   # asked for again in the same test: the same daemon, not reset again

    def get(rig: RigConfig | None = None, args: Iterable[str] = ()) -> Rigsim:
        key = _SessionDaemons.key(rig, args)
        if key not in handed:
            daemon = _rigsim_session_daemons.get(rig, args)
            used.append((daemon, len(daemon.daemon_log())))
            handed[key] = daemon
        return handed[key]

    return get


@pytest.fixture
def rigsim_rig(request: pytest.FixtureRequest, rigsim_session: RigsimFactory) -> Rigsim:
    """The session's daemon on the rig --rigsim-rig=FILE or the ini key rigsim_rig names (the
    built-in default rig without either), reset and its clock restored before each test, as
    rigsim_session gives it."""
    return rigsim_session(_rig_path(request.config))


# ---- what a report gets ----

def _wire_log_text(control: ControlClient, name: str) -> str:
    try:
        answer = control.log(name, WIRE_LOG_LAST)
    except (ControlError, NotControlApi, OSError) as e:
        return f"(no wire log: {e})"
    lines: list[str] = []
    for entry in answer.get("entries", []):
        decoded = entry.get("decoded") or {}
        what = decoded.get("text") or decoded.get("name") or entry.get("hex", "")
        if decoded.get("fields") and "text" not in decoded:
            what += " " + json.dumps(decoded["fields"], separators=(",", ":"))
        notes = "".join(f"\n      note: {n}" for n in entry.get("notes", []))
        lines.append(f"{entry.get('time_ms', 0):>12.3f} ms {entry.get('direction', '?'):<3} {what}"
                     f"  [{entry.get('hex', '')}]{notes}")
    return "\n".join(lines) or "(empty)"


def _daemons_of(item: pytest.Item) -> list[tuple[Rigsim, int]]:
    """Each daemon the test used once, with the log offset of when it first got it."""
    seen: dict[int, tuple[Rigsim, int]] = {}
    for daemon, offset in item.stash.get(_DAEMONS, []):
        seen.setdefault(id(daemon), (daemon, offset))   # a daemon asked for twice: the first offset
    return list(seen.values())


def _attach_logs(item: pytest.Item, report: pytest.TestReport) -> None:
    for i, (daemon, offset) in enumerate(_daemons_of(item)):
        report.sections.append((f"rigsimd log ({i + 1})", daemon.daemon_log()[offset:]))
        control = daemon.control
        if control is None:
            continue
        for name in daemon.used:
            report.sections.append((f"wire log {name} ({i + 1}, last {WIRE_LOG_LAST})",
                                    _wire_log_text(control, name)))


def _noted_mistakes(item: pytest.Item) -> str | None:
    """notes_text() of what the daemons the test used noted, or None."""
    texts: list[str] = []
    for daemon, _ in _daemons_of(item):
        if daemon.control is None or daemon.process is None or daemon.process.poll() is not None:
            continue
        try:
            found = daemon.notes()
        except (ControlError, NotControlApi, OSError) as e:
            texts.append(f"rigsim strict mode: cannot read the wire logs: {e}")
            continue
        if found:
            for n in found:
                if n.device not in daemon.used:
                    daemon.used.append(n.device)   # its wire log goes into the report too
            texts.append(notes_text(found))
    return "\n".join(texts) or None


# pluggy (Debian's 1.0) has no type information: its hookimpl decorator is untyped to mypy, and
# the result object sent into the wrapper is Any.
@pytest.hookimpl(hookwrapper=True)  # type: ignore[misc]
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]) -> Generator[None, Any, None]:
    outcome = yield
    report: pytest.TestReport = outcome.get_result()
    if report.when == "call" and report.passed and _strict(item):
        mistakes = _noted_mistakes(item)
        if mistakes:
            report.outcome = "failed"
            report.longrepr = ("rigsim strict mode (--rigsim-strict, rigsim_strict, "
                               "@pytest.mark.rigsim_strict): " + mistakes)
    if not report.failed or item.stash.get(_ATTACHED, False):
        return
    item.stash[_ATTACHED] = True
    _attach_logs(item, report)
