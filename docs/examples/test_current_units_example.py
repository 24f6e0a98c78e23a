"""What a driver sees change on the units sold today (config/examples/current_units.json: K-Cubes
at firmware "issue-44.1", an MCS at "2.0.1") against the manual's generation (the default rig's
"issue-3" K-Cubes and "1.2.44" MCS). docs/python.md, "Units sold today", explains each."""

import os
import socket
import struct

import pytest

CURRENT_UNITS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "config", "examples",
                             "current_units.json")

HW_REQ_INFO, HW_GET_INFO = 0x0005, 0x0006
MOT_REQ_POSCOUNTER, MOT_GET_POSCOUNTER = 0x0411, 0x0412
Z825_STAGE_ID = 9   # pyLabLib's _autodetect_stage: 9 -> "Z825", 34,304 encoder counts per mm


@pytest.fixture
def current(rigsim_session):
    rig = rigsim_session(CURRENT_UNITS)
    rig.pause()
    return rig


def recv_exact(sock, n):
    data = b""
    while len(data) < n:
        chunk = sock.recv(n - len(data))
        assert chunk, "the connection closed"
        data += chunk
    return data


def apt_ask(address, msg_id, answer_id, param1=0):
    """One APT request (a 6-byte header to the unit at 0x50) and the data of its answer."""
    with socket.create_connection(address, timeout=5) as s:
        s.sendall(struct.pack("<HBBBB", msg_id, param1, 0, 0x50, 0x01))
        got_id, length = struct.unpack("<HH", recv_exact(s, 4))
        recv_exact(s, 2)   # destination | 0x80, source
        assert got_id == answer_id
        return recv_exact(s, length)


def mcs_ask(address, line):
    with socket.create_connection(address, timeout=5) as s:
        s.sendall(line.encode() + b"\n")
        answer = b""
        while not answer.endswith(b"\n"):
            answer += s.recv(100)
    return answer.decode().strip()


def test_a_kdc101_names_its_stage_only_at_issue_44_1(rig, current):
    """pyLabLib's KinesisMotor(scale="stage") reads the stage type word at data 76 of HW_GET_INFO.
    An issue-3 unit leaves it 0: pyLabLib warns "can't recognize the stage; assuming step scale
    of 1" and takes positions in raw encoder counts (move_by(1e-3) is 1 count, not 1 mm)."""
    today = apt_ask(current.endpoint("kdc101").address, HW_REQ_INFO, HW_GET_INFO)
    manual = apt_ask(rig.endpoint("kdc101").address, HW_REQ_INFO, HW_GET_INFO)
    assert struct.unpack_from("<H", today, 76)[0] == Z825_STAGE_ID
    assert struct.unpack_from("<H", manual, 76)[0] == 0
    assert today[4:10] == manual[4:10] == b"KDC101"


def position_counter(rig, name):
    data = apt_ask(rig.endpoint(name).address, MOT_REQ_POSCOUNTER, MOT_GET_POSCOUNTER, param1=1)
    return struct.unpack_from("<i", data, 2)[0]


def test_a_kst101_counts_16_microsteps_for_the_manuals_one(rig, current):
    """At issue-44.1 a KST101 counts 2048 microsteps per full step: a ZST225B moved 1 mm counts
    2,008,646 more where the issue-3 unit counts 125,540 (and velocities scale by 53.68)."""
    counts = {}
    for name, r in (("today", current), ("manual", rig)):
        before = position_counter(r, "kst101")
        at_m = r.state("kst101")["channels"][0]["position_si"]
        r.set("kst101", 0, position_si=at_m + 0.001)   # the stage put 1 mm further along
        counts[name] = position_counter(r, "kst101") - before
    assert counts == {"today": 2_008_646, "manual": 125_540}


def test_an_mcs_at_2_0_1_reports_its_interface_and_takes_the_later_search_directions(rig, current):
    assert mcs_ask(current.endpoint("mcs0").address, ":GIV") == ":IV2,0,1"
    assert mcs_ask(rig.endpoint("mcs0").address, ":GIV") == ":IV1,2,44"
    # FRM direction 2 (forward, then backward): a 2.0.1 controller starts the search, the
    # manual's answers Invalid Parameter.
    assert mcs_ask(current.endpoint("mcs0").address, ":FRM0,2,0,0") == ":E0,0"
    assert mcs_ask(rig.endpoint("mcs0").address, ":FRM0,2,0,0") == ":E0,7"
