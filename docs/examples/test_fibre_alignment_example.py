"""Fibre alignment on config/examples/fibre_alignment.json: three KDC101 + Z825B coarse stages
(X, Y, Z stacked) carry a TPZ001 piezo (with a TSG001 strain gauge, closed loop) that pushes the
fibre holder along X; the fibre tip is a tool point 25 mm ahead of the holder, the waveguide a tool
point on the chip's facet. The test aligns the tip to 5 µm in front of the waveguide the way a lab
script would: it reads both poses from the control API (rig.pose), drives the coarse stages over
their APT wire to 10 µm short, then closes the last micrometres with the piezo's closed loop
(PZ_SET_OUTPUTPOS, p.97), and checks the pose the world reports."""

import os
import struct

import pytest
import serial

from apt_client import AptClient

COUNTS_PER_MM = 34304            # Z825B (config/stages/Z825B.json)
PIEZO_TRAVEL_UM = 20             # fine_x's actuator
GAP_UM = 5                       # the fibre stops this far in front of the facet
HOST, UNIT = 0x01, 0x50
PZ_SET_POSCONTROLMODE, PZ_SET_OUTPUTPOS, PZ_REQ_OUTPUTPOS, PZ_GET_OUTPUTPOS = 0x0640, 0x0646, 0x0647, 0x0648

FIBRE_RIG = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir,
                         "config", "examples", "fibre_alignment.json")


@pytest.fixture
def fibre_rig(rigsim_session):
    rig = rigsim_session(FIBRE_RIG)
    rig.pause()
    return rig


def position_mm(rig, name):
    return list(rig.pose(name).position_mm)


def home_all(rig, stages):
    for stage in stages.values():
        stage.home()
    rig.run_until_idle(600_000)
    for stage in stages.values():
        stage.wait_homed(timeout_s=10)


def move_by(rig, stage, delta_mm):
    start, _ = stage.status()
    target = start + round(delta_mm * COUNTS_PER_MM)
    stage.move_absolute(target)
    rig.run_until_idle(600_000)
    assert stage.wait_move(timeout_s=10) == target


def piezo_request(port, message_id, p1=1, p2=0):
    port.write(struct.pack("<HBBBB", message_id, p1, p2, UNIT, HOST))


def set_fine_um(rig, port, extension_um):
    """Closed loop on the strain gauge; set point as a fraction of the actuator's travel."""
    piezo_request(port, PZ_SET_POSCONTROLMODE, 1, 2)
    code = round(extension_um / PIEZO_TRAVEL_UM * 32767)
    port.write(struct.pack("<HHBB", PZ_SET_OUTPUTPOS, 4, UNIT | 0x80, HOST) + struct.pack("<HH", 1, code))
    piezo_request(port, PZ_REQ_OUTPUTPOS)          # answered once the set point is taken
    answer = port.read(6 + 4)
    assert struct.unpack_from("<H", answer)[0] == PZ_GET_OUTPUTPOS
    rig.step(2000)                                  # the loop settles (2 s of stepped time)


def test_the_fibre_tip_is_aligned_to_the_waveguide(fibre_rig):
    rig = fibre_rig
    stages = {axis: AptClient(rig.endpoint(f"coarse_{axis}").url) for axis in "xyz"}
    piezo = serial.serial_for_url(rig.endpoint("fine_x").url, baudrate=115200, timeout=2)
    try:
        home_all(rig, stages)
        target = position_mm(rig, "waveguide")
        target[0] -= GAP_UM / 1000

        # Coarse: Y and Z onto the waveguide, X to 10 µm short of the target (safe approach).
        tip = position_mm(rig, "fibre_tip")
        move_by(rig, stages["y"], target[1] - tip[1])
        move_by(rig, stages["z"], target[2] - tip[2])
        move_by(rig, stages["x"], target[0] - 0.010 - tip[0])

        # Fine: the piezo closes what is left along X (about 10 µm, within its 20 µm travel).
        tip = position_mm(rig, "fibre_tip")
        extension_um = rig.pose("fine_x").joint["position"] * 1000 + (target[0] - tip[0]) * 1000
        assert 0 < extension_um < PIEZO_TRAVEL_UM
        set_fine_um(rig, piezo, extension_um)

        tip = position_mm(rig, "fibre_tip")
        # X within 10 nm (the gauge's noise is 2 nm), Y and Z within half an encoder count.
        assert tip[0] == pytest.approx(target[0], abs=10e-6)
        assert tip[1] == pytest.approx(target[1], abs=0.5 / COUNTS_PER_MM + 1e-9)
        assert tip[2] == pytest.approx(target[2], abs=0.5 / COUNTS_PER_MM + 1e-9)
        # The holder's box never touched the chip's.
        assert rig.frames()["collisions"] == []
    finally:
        for stage in stages.values():
            stage.close()
        piezo.close()
