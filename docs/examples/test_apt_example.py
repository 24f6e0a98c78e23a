"""The APT client of apt_client.py against rigsim's KDC101 with a Z825B (kdc101 of the default
rig)."""

import pytest

from apt_client import CURRENT_LIMIT, HOMED, HOMING, MOTION_ERROR, AptError

COUNTS_PER_MM = 34304   # Z8 series actuators (Thorlabs' APT scaling for the Z825B)


def test_homing_finishes(apt, finish):
    _, bits = apt.home()
    assert bits & HOMING
    finish()
    apt.wait_homed(timeout_s=120)
    position, bits = apt.status()
    assert bits & HOMED and not bits & HOMING
    assert position == 0


def test_a_move_after_homing_reaches_its_target(apt, finish):
    apt.home()
    finish()
    apt.wait_homed(timeout_s=120)
    apt.move_absolute(5 * COUNTS_PER_MM)
    finish()
    assert apt.wait_move() == 5 * COUNTS_PER_MM


def test_a_stall_stops_the_move_with_an_error(rig, apt, finish):
    rig.inject("kdc101", "stall", channel=0)
    start, _ = apt.status()
    apt.move_absolute(start + 5 * COUNTS_PER_MM)
    finish()
    with pytest.raises(AptError) as error:
        apt.wait_move()
    assert error.value.status & (MOTION_ERROR | CURRENT_LIMIT)
    assert apt.faults, "no HW_RICHRESPONSE came"
    assert error.value.code is not None   # a KDC101 sends the verbose form, with its code
