"""rigsimd's RFC 2217 endpoint (docs/cli.md, "RFC 2217") with pyserial's own rfc2217:// client:
the port opens, takes its settings and RTS/DTR without any shim, reads its modem lines, and
carries the unit's bytes both ways, 0xFF included; a baud rate the client sets there is the rate
the device sees (a baud_mismatch fault garbles it as on the pty)."""

from __future__ import annotations

import struct
import time

import pytest

serial = pytest.importorskip("serial")

HW_REQ_INFO = struct.pack("<HBBBB", 0x0005, 0, 0, 0x50, 0x01)


def wait_for(predicate, timeout_s: float = 5.0) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(0.01)
    return predicate()


def test_pyserial_sets_up_the_port_and_talks_to_the_unit(rigsim):
    rig = rigsim(args=["--rfc2217"])
    endpoint = rig.endpoint("kdc101")
    assert endpoint.rfc2217 and endpoint.rfc2217_url == "rfc2217://" + endpoint.rfc2217
    port = serial.serial_for_url(endpoint.rfc2217_url, baudrate=115200, timeout=2)
    try:
        port.rts = True   # the APT set-up (pyLabLib, Thorlabs' own): no LD_PRELOAD shim needed
        port.dtr = True
        assert port.cts and port.dsr and port.cd
        port.write(HW_REQ_INFO)
        info = port.read(90)
        assert len(info) == 90 and struct.unpack_from("<H", info)[0] == 0x0006 and b"KDC101" in info
        # A position counter of -1 is 0xFFFFFFFF each way: escaped by pyserial, by the server.
        port.write(struct.pack("<HHBB", 0x0410, 6, 0xD0, 0x01) + struct.pack("<Hi", 1, -1))   # MOT_SET_POSCOUNTER
        port.write(struct.pack("<HBBBB", 0x0411, 1, 0, 0x50, 0x01))                         # MOT_REQ_POSCOUNTER
        answer = port.read(12)
        assert answer[:2] == b"\x12\x04" and struct.unpack_from("<i", answer, 8)[0] == -1
    finally:
        port.close()
    assert "RFC 2217: " not in rig.daemon_log()   # nothing it sent was ignored


def test_a_baud_rate_set_over_rfc2217_is_the_rate_the_device_sees(rigsim):
    rig = rigsim(args=["--rfc2217"])
    endpoint = rig.endpoint("kdc101")
    port = serial.serial_for_url(endpoint.rfc2217_url, baudrate=115200, timeout=1)
    try:
        rig.inject("kdc101", "baud_mismatch")
        port.write(HW_REQ_INFO)
        assert len(port.read(90)) == 90            # at the unit's rate: nothing changes
        port.baudrate = 9600                       # the client at the wrong rate
        assert wait_for(lambda: "the client set 9600 baud" in rig.daemon_log())
        port.write(HW_REQ_INFO)
        garbled = port.read(90)
        assert len(garbled) < 90                   # the unit read garbage: no HW_GET_INFO
        assert rig.state("kdc101")["link"]["corrupted_bytes"] > 0
    finally:
        port.close()


def test_the_endpoint_is_listed_by_the_control_api_and_rigsimctl(rigsim):
    from rigsim.cli import render_table
    rig = rigsim(args=["--rfc2217"])
    state = rig.rig_state()
    address = rig.endpoint("kdc101").rfc2217
    assert [d for d in state["devices"] if d["name"] == "kdc101"][0]["rfc2217"] == address
    assert rig.state("kdc101")["endpoints"]["rfc2217"] == address
    table = render_table("rig", state)
    assert table.splitlines()[0].split()[-1] == "rfc2217" and address in table


def test_without_the_flag_or_the_key_no_device_has_one(rigsim):
    from rigsim.cli import render_table
    rig = rigsim()
    assert rig.endpoint("kdc101").rfc2217 == ""
    assert "rfc2217" not in rig.rig_state()["devices"][0]
    assert "rfc2217" not in render_table("rig", rig.rig_state())
    with pytest.raises(ValueError, match="no RFC 2217 endpoint"):
        rig.endpoint("kdc101").rfc2217_url
