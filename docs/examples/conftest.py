"""Fixtures of the example suite (docs/python.md#examples).

The suite runs on the default rig (mcs0, an MCS-3D; kdc101, a KDC101 with a Z825B), one daemon
for the whole session (`rigsim_session`, reset before each test); the LUT example runs on its own
rig, bpc303_rig.json (a BPC303 with one piezo bay), through `piezo_rig`. By default the clock is
paused and moves are finished with run_until_idle(); with RIGSIM_REAL_TIME=1 the clock runs in
real time and the clients wait as they would on hardware: the same tests, for comparing wall
times (pytest --durations=0).
"""

import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))   # the example clients

from apt_client import AptClient   # noqa: E402
from mcs_client import McsClient   # noqa: E402


REAL_TIME = os.environ.get("RIGSIM_REAL_TIME") == "1"
PIEZO_RIG = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bpc303_rig.json")


@pytest.fixture
def rig(rigsim_session):
    rig = rigsim_session()
    if not REAL_TIME:
        rig.pause()
    return rig


@pytest.fixture
def piezo_rig(rigsim_session):
    """The session's daemon on bpc303_rig.json, paused (the LUT example steps the clock)."""
    rig = rigsim_session(PIEZO_RIG)
    rig.pause()
    return rig


@pytest.fixture
def finish(rig):
    """finish(): let every move in progress end. Stepped time: run_until_idle() (milliseconds of
    wall time); real time: nothing, the client waits as on hardware."""
    def finish_moves(max_ms=600_000):
        if not REAL_TIME:
            return rig.run_until_idle(max_ms)
        return None
    return finish_moves


@pytest.fixture
def mcs(rig):
    client = McsClient(rig.endpoint("mcs0").url)
    yield client
    client.close()


@pytest.fixture
def apt(rig):
    client = AptClient(rig.endpoint("kdc101").url)
    yield client
    client.close()
