"""The MCS client of mcs_client.py against rigsim's MCS-3D (mcs0 of the default rig)."""

import pytest

from mcs_client import END_STOP_REACHED, McsError


def test_move_and_read_the_position(mcs, finish):
    start = mcs.position_nm(0)
    target = start + 3_000_000   # 3 mm
    mcs.move_absolute(0, target)
    finish()
    assert mcs.wait_stopped(0) == 0
    assert mcs.position_nm(0) == target


def test_a_stall_is_reported_as_end_stop_reached(rig, mcs, finish):
    rig.inject("mcs0", "stall", channel=0)
    mcs.set_asynchronous()
    start = mcs.position_nm(0)
    mcs.move_absolute(0, start + 3_000_000)
    finish()
    with pytest.raises(McsError) as error:
        mcs.wait_stopped(0)
    assert (error.value.channel, error.value.code) == (0, END_STOP_REACHED)
    assert mcs.status(0) == 0
    assert mcs.position_nm(0) != start + 3_000_000
