"""The default rig's MCS2 (`mcs2`, three linear type-300 positioners) driven as the public drivers
drive it, on the paused clock. The drivers themselves (EPICS motorSmarAct is C++ in an IOC, BLISS
needs gevent and its own framework) do not run here and this suite installs nothing from the network,
so the command sequences they send are written out, each citing where it comes from
(docs/protocol/mcs2.md):

- EPICS motorSmarAct's MCS2 driver (smarActApp/src/smarActMCS2MotorDriver.cpp): CR LF both ways,
  settings never answered, at start-up `:SYST:ERR:COUN?` and `:SYST:ERR?` until the queue is empty,
  `:DEV:SNUM?`, `:CHAN%d:HOLD -1`; each poll `:CHAN%d:STAT?`, `:SENS:MODE?`, `:POS?`, `:POS:TARG?`,
  `:PTYP?`; a move `:MMOD`, `:ACC %f`, `:VEL %f`, `:MOVE%d %f`; a homing `:REF:OPT`, `:REF%d`.
- BLISS (bliss/controllers/motors/smaract_mcs2.py): every command followed by `:SYST:ERR:COUN?`,
  a non-zero count read with `:SYST:ERR?` and split at the comma; `:MOD:STAT?` without an index.
- kamzik3 reads each error with the pattern `([-0-9]+),"([\\w ]+)"`."""

import os
import re
import socket
import time

import pytest

ACTIVELY_MOVING, CLOSED_LOOP_ACTIVE, IS_REFERENCED, END_STOP_REACHED = 0x1, 0x2, 0x80, 0x100
KAMZIK3_ERROR = re.compile(r'([-0-9]+),"([\w ]+)"')
REAL_TIME = os.environ.get("RIGSIM_REAL_TIME") == "1"   # conftest.py: the clock runs, clients wait


class Mcs2Line:
    """One TCP connection: write a line ended by CR LF, read one ended by CR LF."""

    def __init__(self, address):
        self.sock = socket.create_connection(address, timeout=5)
        self.answers = self.sock.makefile("rb")

    def write(self, command):
        self.sock.sendall(command.encode() + b"\r\n")

    def query(self, command):
        self.write(command)
        line = self.answers.readline()
        assert line.endswith(b"\r\n"), line
        return line[:-2].decode()

    def close(self):
        self.answers.close()
        self.sock.close()


@pytest.fixture
def mcs2(rig):
    line = Mcs2Line(rig.endpoint("mcs2").address)
    yield line
    line.close()


def epics_clear_errors(line):
    """clearErrors(): the count, then each error by its leading number (atoi)."""
    codes = []
    for _ in range(int(line.query(":SYST:ERR:COUN?"))):
        codes.append(int(line.query(":SYST:ERR?").split(",")[0]))
    return codes


def epics_poll(line, axis):
    status = int(line.query(":CHAN%d:STAT?" % axis))
    sensor_mode = int(line.query(":CHAN%d:SENS:MODE?" % axis))
    position = float(line.query(":CHAN%d:POS?" % axis))
    target = float(line.query(":CHAN%d:POS:TARG?" % axis))
    positioner_type = int(line.query(":CHAN%d:PTYP?" % axis))
    return status, sensor_mode, position, target, positioner_type


def wait_until_stopped(line, axis, timeout_s=30):
    """Polls as EPICS does until ACTIVELY_MOVING clears (at once after finish() on the stepped clock)."""
    deadline = time.monotonic() + timeout_s
    while int(line.query(":CHAN%d:STAT?" % axis)) & ACTIVELY_MOVING:
        assert time.monotonic() < deadline, "still moving"
        time.sleep(0.05)


def test_epics_motorsmaract_start_up_poll_move_and_home(rig, mcs2, finish):
    assert epics_clear_errors(mcs2) == []
    assert mcs2.query(":DEV:SNUM?") == '"MCS2-00000001"'   # printed as "Device Name: %s"
    mcs2.write(":CHAN0:HOLD %d" % -1)
    assert epics_clear_errors(mcs2) == []

    status, sensor_mode, position, target, ptype = epics_poll(mcs2, 0)
    assert status & ACTIVELY_MOVING == 0 and sensor_mode == 1 and ptype == 300
    assert (position, target) == (0.0, 0.0)

    # A closed-loop absolute move of 1 mm at 1 mm/s, values printed with %f.
    mcs2.write(":CHAN%d:MMOD %d" % (0, 0))
    mcs2.write(":CHAN%d:ACC %f" % (0, 0.0))
    mcs2.write(":CHAN%d:VEL %f" % (0, 1e9))
    mcs2.write(":MOVE%d %f" % (0, 1e9))
    status, _, _, target, _ = epics_poll(mcs2, 0)
    assert status & (ACTIVELY_MOVING | CLOSED_LOOP_ACTIVE) == ACTIVELY_MOVING | CLOSED_LOOP_ACTIVE
    assert target == 1e9
    if not REAL_TIME:
        rig.step(500)
        assert epics_poll(mcs2, 0)[2] == 5e8
    finish()
    wait_until_stopped(mcs2, 0)
    status, _, position, _, _ = epics_poll(mcs2, 0)
    assert status & ACTIVELY_MOVING == 0 and position == 1e9

    # Homing forwards with auto zero: the mark is at the physical zero, 2.5 mm behind the start.
    mcs2.write(":CHAN%d:REF:OPT %d" % (1, 4))
    assert epics_clear_errors(mcs2) == []   # the driver clears the queue after each homing command,
    mcs2.write(":REF%d" % 1)
    assert epics_clear_errors(mcs2) == []   # which also orders the homing before the clock's run below
    finish()
    wait_until_stopped(mcs2, 1)
    status, _, position, _, _ = epics_poll(mcs2, 1)
    assert status & IS_REFERENCED and position == 0.0
    assert epics_clear_errors(mcs2) == []


def test_bliss_checks_the_error_count_after_each_command(mcs2):
    def command(text):
        mcs2.write(text)
        count = int(mcs2.query(":SYST:ERR:COUN?"))
        if count:
            err = mcs2.query(":SYST:ERR?").split(",")
            return int(err[0]), err[1].strip()
        return None

    assert command(":CHAN2:MMOD 0") is None
    assert command(":CHAN7:MMOD 0") == (34, '"Invalid channel index"')
    assert command(":CHAN2:MMOD 9") == (19, '"Invalid parameter"')
    assert mcs2.query(":MOD:STAT?") == "1"          # sensor module present
    assert mcs2.query(":CHAN2:PTYPE?") == "300"     # the long form of PTYPe


def test_every_error_text_fits_kamzik3s_pattern(mcs2):
    for bad in (":CHAN0:STAT?!", ":CHAN9:POS?", ":CHAN0:NOPE?", ":CHAN0:VEL 1x", ":CHAN0:VEL -1",
                ":CHAN0:CLIN 2", ":DEV:HMOD:LOPT?", ":STR:BFRE?", ":CHAN0:POS? 1"):
        mcs2.write(bad)
        entry = mcs2.query(":SYST:ERR:NEXT?")
        assert KAMZIK3_ERROR.fullmatch(entry), entry
    assert mcs2.query(":SYST:ERR?") == '0,"No Error"'
