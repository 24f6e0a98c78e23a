"""A KIM101 piezo inertia motor controller (config/examples/current_units.json) driven as the public
drivers drive it, on the paused clock. The drivers themselves (pyLabLib, InstrumentKit, QMI) are not
Debian packages and this suite installs nothing from the network, so their byte sequences are written
out here, each citing where it comes from (docs/protocol/apt.md "Units of today"):

- pyLabLib's KinesisPiezoMotor enables the channel with the PZMOT sub-message 0x2B (its index, 1..4),
  then moves it with PZMOT_MOVE_ABSOLUTE addressed by the channel's bit (1, 2, 4, 8) and reads the
  position with PZMOT_REQ_PARAMS sub-message 0x05 (pylablib/devices/Thorlabs/kinesis.py).
- InstrumentKit addresses every channel by its index (thorlabsapt.py, its issue 372): channel 3 as 3,
  which the unit takes for no channel at all."""

import os
import socket
import struct

import pytest

CURRENT_UNITS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "config", "examples",
                             "current_units.json")

PZMOT_SET_PARAMS, PZMOT_REQ_PARAMS, PZMOT_GET_PARAMS = 0x08C0, 0x08C1, 0x08C2
PZMOT_MOVE_ABSOLUTE, PZMOT_MOVE_COMPLETED = 0x08D4, 0x08D6
SUB_POS_COUNTS, SUB_CHAN_ENABLE_MODE = 0x05, 0x2B


@pytest.fixture
def kim(rigsim_session):
    rig = rigsim_session(CURRENT_UNITS)
    rig.pause()
    with socket.create_connection(rig.endpoint("kim101").address, timeout=5) as s:
        yield rig, s


def recv_exact(sock, n):
    data = b""
    while len(data) < n:
        chunk = sock.recv(n - len(data))
        assert chunk, "the connection closed"
        data += chunk
    return data


def read_message(sock):
    """The next APT message from the unit: (its ID, its data)."""
    msg_id, length, dest, _ = struct.unpack("<HHBB", recv_exact(sock, 6))
    return msg_id, recv_exact(sock, length) if dest & 0x80 else b""


def send_data(sock, msg_id, data):
    sock.sendall(struct.pack("<HHBB", msg_id, len(data), 0x50 | 0x80, 0x01) + data)


def position(sock, channel_bit):
    sock.sendall(struct.pack("<HBBBB", PZMOT_REQ_PARAMS, SUB_POS_COUNTS, channel_bit, 0x50, 0x01))
    msg_id, data = read_message(sock)
    assert msg_id == PZMOT_GET_PARAMS
    sub, chan, steps = struct.unpack_from("<HHl", data)
    assert (sub, chan) == (SUB_POS_COUNTS, channel_bit)
    return steps


def test_pylablib_moves_channel_3_by_its_bit(kim):
    rig, s = kim
    send_data(s, PZMOT_SET_PARAMS, struct.pack("<HH", SUB_CHAN_ENABLE_MODE, 3))   # enable channel 3 alone
    send_data(s, PZMOT_MOVE_ABSOLUTE, struct.pack("<Hl", 0x04, 500))            # channel 3's bit
    rig.step(1000)   # 500 steps at 500 steps/s, ramping at 100,000 steps/s²: 1.005 s
    rig.step(5)
    msg_id, data = read_message(s)
    assert msg_id == PZMOT_MOVE_COMPLETED
    assert struct.unpack_from("<Hl", data) == (0x04, 500)
    assert position(s, 0x04) == 500
    assert position(s, 0x01) == 0


def test_instrumentkit_channel_3_as_an_index_moves_nothing(kim):
    rig, s = kim
    send_data(s, PZMOT_SET_PARAMS, struct.pack("<HH", SUB_CHAN_ENABLE_MODE, 3))
    send_data(s, PZMOT_MOVE_ABSOLUTE, struct.pack("<Hl", 3, 500))   # 3: no single channel bit
    rig.step(2000)
    s.settimeout(0.3)
    with pytest.raises(socket.timeout):
        s.recv(1)                                                   # no MOVE_COMPLETED
    s.settimeout(5)
    assert position(s, 0x04) == 0
    actuators = rig.device("kim101").channel(0)["actuators"]
    assert [a["moving"] for a in actuators] == [False, False, False, False]
    assert actuators[2]["position"] == 0
