"""pytest plugin: the `rigsim` fixture factory and its session-scoped variant `rigsim_session`.

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

Every daemon `rigsim` started is stopped (its ptys removed) when the test ends; `rigsim_session`
daemons when the session ends. When a test fails, the report gets each daemon's log (for a
session daemon: the part written during the test) and the wire log of every device the test
used (called endpoint(), state(), set(), inject() or log() on). rigsimd is found by
--rigsimd PATH, the `rigsimd` ini key, $RIGSIMD, or PATH, in that order.

A rig's frames and tool points are read through the Rigsim: rig.pose(name) (world and
parent-relative placement), rig.frames() (all of them).

Enable it with `-p rigsim.pytest_plugin` or `pytest_plugins = ["rigsim.pytest_plugin"]` in a
conftest.py (an installed package registers it by entry point).
"""

import json

import pytest

from rigsim.control import ControlError
from rigsim.daemon import Rigsim

# (daemon, offset of its log when the test got it) for every daemon a test used.
_DAEMONS = pytest.StashKey[list]()

WIRE_LOG_LAST = 200   # entries of each device's wire log attached to a failed test's report


def pytest_addoption(parser):
    parser.addoption("--rigsimd", default=None, help="path of the rigsimd binary for the rigsim fixtures")
    parser.addini("rigsimd", default=None, help="path of the rigsimd binary for the rigsim fixtures")


def _rigsimd_path(config):
    return config.getoption("--rigsimd") or config.getini("rigsimd") or None


def _used_by(item):
    if _DAEMONS not in item.stash:
        item.stash[_DAEMONS] = []
    return item.stash[_DAEMONS]


@pytest.fixture
def rigsim(request):
    """Factory: rigsim(rig=None, args=()) starts rigsimd on `rig` and returns a Rigsim; stopped
    when the test ends."""
    started = []
    used = _used_by(request.node)

    def start(rig=None, args=()):
        daemon = Rigsim(rig, rigsimd=_rigsimd_path(request.config), args=args)
        started.append(daemon)
        used.append((daemon, 0))
        return daemon.start()

    yield start
    for daemon in started:
        daemon.stop()


class _SessionDaemons:
    """The daemons of the session, one per (rig, args), and the clock each started with."""

    def __init__(self, rigsimd):
        self.rigsimd = rigsimd
        self.daemons = {}

    @staticmethod
    def key(rig, args):
        return (json.dumps(rig, sort_keys=True, default=str), tuple(args))

    def get(self, rig, args):
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

    def _reset(self, daemon, clock, rig, args, key):
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

    def stop_all(self):
        for daemon, _ in self.daemons.values():
            daemon.stop()


@pytest.fixture(scope="session")
def _rigsim_session_daemons(pytestconfig):
    daemons = _SessionDaemons(_rigsimd_path(pytestconfig))
    yield daemons
    daemons.stop_all()


@pytest.fixture
def rigsim_session(request, _rigsim_session_daemons):
    """Factory: rigsim_session(rig=None, args=()) returns the session's daemon on `rig` (started
    on first use, stopped at the end of the session), reset() and its clock restored first."""
    used = _used_by(request.node)
    handed = {}   # asked for again in the same test: the same daemon, not reset again

    def get(rig=None, args=()):
        key = _SessionDaemons.key(rig, args)
        if key not in handed:
            daemon = _rigsim_session_daemons.get(rig, args)
            used.append((daemon, len(daemon.daemon_log())))
            handed[key] = daemon
        return handed[key]

    return get


def _wire_log_text(daemon, name):
    try:
        answer = daemon.control.log(name, WIRE_LOG_LAST)
    except (ControlError, OSError) as e:
        return f"(no wire log: {e})"
    lines = []
    for e in answer.get("entries", []):
        decoded = e.get("decoded") or {}
        what = decoded.get("text") or decoded.get("name") or e.get("hex", "")
        if decoded.get("fields") and "text" not in decoded:
            what += " " + json.dumps(decoded["fields"], separators=(",", ":"))
        notes = "".join(f"\n      note: {n}" for n in e.get("notes", []))
        lines.append(f"{e.get('time_ms', 0):>12.3f} ms {e.get('direction', '?'):<3} {what}"
                     f"  [{e.get('hex', '')}]{notes}")
    return "\n".join(lines) or "(empty)"


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if report.when != "call" or not report.failed:
        return
    seen = {}
    for daemon, offset in item.stash.get(_DAEMONS, []):
        seen.setdefault(id(daemon), (daemon, offset))   # a daemon asked for twice: the first offset
    for i, (daemon, offset) in enumerate(seen.values()):
        report.sections.append((f"rigsimd log ({i + 1})", daemon.daemon_log()[offset:]))
        if daemon.control is None:
            continue
        for name in daemon.used:
            report.sections.append((f"wire log {name} ({i + 1}, last {WIRE_LOG_LAST})",
                                    _wire_log_text(daemon, name)))
