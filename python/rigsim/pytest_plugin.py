"""pytest plugin: the `rigsim` fixture factory.

    def test_home(rigsim):
        rig = rigsim("my-rig.json")          # or a dict, or no argument for the default rig
        rig.pause()
        ...

Every daemon a test started is stopped (its ptys removed) when the test ends; when the test
fails, each daemon's log is attached to the report. rigsimd is found by --rigsimd PATH, the
`rigsimd` ini key, $RIGSIMD, or PATH, in that order.

Enable it with `-p rigsim.pytest_plugin` or `pytest_plugins = ["rigsim.pytest_plugin"]` in a
conftest.py (an installed package registers it by entry point).
"""

import pytest

from rigsim.daemon import Rigsim

_DAEMONS = pytest.StashKey[list]()


def pytest_addoption(parser):
    parser.addoption("--rigsimd", default=None, help="path of the rigsimd binary for the rigsim fixture")
    parser.addini("rigsimd", default=None, help="path of the rigsimd binary for the rigsim fixture")


def _rigsimd_path(config):
    return config.getoption("--rigsimd") or config.getini("rigsimd") or None


@pytest.fixture
def rigsim(request):
    """Factory: rigsim(rig=None, args=()) starts rigsimd on `rig` and returns a Rigsim."""
    started = []
    request.node.stash[_DAEMONS] = started

    def start(rig=None, args=()):
        daemon = Rigsim(rig, rigsimd=_rigsimd_path(request.config), args=args)
        started.append(daemon)
        return daemon.start()

    yield start
    for daemon in started:
        daemon.stop()


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if report.when != "call" or not report.failed:
        return
    for i, daemon in enumerate(item.stash.get(_DAEMONS, [])):
        report.sections.append((f"rigsimd log ({i + 1})", daemon.log()))
