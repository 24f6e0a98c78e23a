"""The rigsim package and its pytest plugin against the real rigsimd (--rigsimd PATH)."""

import os
import socket
import time

import pytest

from rigsim import ControlClient, ControlError, RigsimError


def mcs_ask(sock, command):
    """Send one MCS command line and return the answer line (without the newline)."""
    sock.sendall(command.encode() + b"\n")
    answer = b""
    deadline = time.monotonic() + 5
    while not answer.endswith(b"\n"):
        assert time.monotonic() < deadline, f"no answer to {command!r}"
        answer += sock.recv(256)
    return answer.decode().strip()


def test_default_rig_endpoints_and_clock(rigsim):
    rig = rigsim()
    mcs0 = rig.endpoint("mcs0")
    assert mcs0.protocol == "mcs"
    assert os.path.exists(mcs0.pty)
    assert mcs0.url.startswith("socket://127.0.0.1:")
    clock = rig.clock()
    assert clock["paused"] is False
    assert clock["tick_hz"] == 1000
    assert [d["name"] for d in rig.state()["devices"]] == sorted(rig.endpoints, key=list(rig.endpoints).index)
    with pytest.raises(KeyError, match="no device 'nope'"):
        rig.endpoint("nope")


def test_a_paused_move_finishes_on_step(rigsim):
    rig = rigsim()
    rig.pause()
    running = rigsim()   # the same move on a running clock: it measures the wall time that passes
    with socket.create_connection(rig.endpoint("mcs0").address, timeout=5) as s, \
            socket.create_connection(running.endpoint("mcs0").address, timeout=5) as r:
        start = mcs_ask(s, ":GP0")
        assert start.startswith(":P0,")
        target = int(start[4:]) + 5_000_000   # 5 mm away: half a second at the default speed
        assert mcs_ask(s, f":MPA0,{target},0") == ":E0,0"
        running_start = int(mcs_ask(r, ":GP0")[4:])
        assert mcs_ask(r, f":MPA0,{running_start + 5_000_000},0") == ":E0,0"
        # Wall time passes until the running clock's move is 3 mm along; the paused clock does not
        # pass: polled all along, its move never leaves the start.
        deadline = time.monotonic() + 10
        while int(mcs_ask(r, ":GP0")[4:]) < running_start + 3_000_000:
            assert mcs_ask(s, ":GP0") == start
            assert time.monotonic() < deadline, "the move on the running clock did not get 3 mm along"
            time.sleep(0.01)
        assert mcs_ask(s, ":GP0") == start
        assert mcs_ask(s, ":GS0") != ":S0,0"   # still moving
        rig.step(10_000)   # 10 s of clock time: the move is done
        assert mcs_ask(s, ":GP0") == f":P0,{target}"


def test_run_until_idle_finishes_a_move_without_waiting(rigsim):
    rig = rigsim()
    rig.pause()
    with socket.create_connection(rig.endpoint("mcs0").address, timeout=5) as s:
        start = int(mcs_ask(s, ":GP0")[4:])
        assert mcs_ask(s, f":MPA0,{start + 5_000_000},0") == ":E0,0"
        before = rig.clock()["now_ms"]
        reached = rig.run_until_idle(600_000)
        assert before < reached["now_ms"] < before + 600_000
        assert mcs_ask(s, ":GP0") == f":P0,{start + 5_000_000}"


def test_a_bad_request_raises_control_error(rigsim):
    rig = rigsim()
    with pytest.raises(ControlError) as e:
        rig.control.request("POST", "/api/clock", {"step_ms": -1})
    assert e.value.status == 400
    assert "step_ms" in e.value.message


def test_the_daemon_takes_its_fresh_token_only(rigsim):
    rig = rigsim()
    assert rig.token and len(rig.token) >= 32
    token_file = os.path.join(rig.dir, "control-token")
    assert os.stat(token_file).st_mode & 0o777 == 0o600
    assert rig.token not in " ".join(open(f"/proc/{rig.process.pid}/cmdline").read().split("\0"))
    with pytest.raises(ControlError) as e:
        ControlClient(rig.control.url, token="").clock()
    assert e.value.status == 401
    with pytest.raises(ControlError) as e:
        ControlClient(rig.control.url, token=rig.token + "x").clock()
    assert e.value.status == 401
    assert ControlClient(rig.control.url, token=rig.token).clock()["tick_hz"] == 1000


def test_a_token_of_its_own_in_args_is_kept(rigsim):
    rig = rigsim(args=["--control-token", "mine-1234"])
    assert rig.token == "mine-1234"
    assert rig.clock()["tick_hz"] == 1000


def test_a_bad_rig_raises_with_the_daemon_message(rigsim):
    with pytest.raises(RigsimError, match="exited with status 2"):
        rigsim({"devices": "not a list"})


def test_a_failed_test_gets_the_daemon_log_attached(pytester, request):
    rigsimd = request.config.getoption("--rigsimd")
    pytester.makepyfile(
        """
        def test_fails(rigsim):
            rigsim()
            assert False, "failing on purpose"
        """
    )
    result = pytester.runpytest("-p", "rigsim.pytest_plugin", "--rigsimd", rigsimd)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*rigsimd log (1)*", "*listening on tcp*"])


def test_daemons_are_stopped_and_their_ptys_removed_after_the_test(pytester, request):
    rigsimd = request.config.getoption("--rigsimd")
    pytester.makepyfile(
        """
        import os
        PTYS = []
        def test_uses(rigsim):
            PTYS.append(rigsim().endpoint("mcs0").pty)
        def test_after():
            assert PTYS and not os.path.exists(PTYS[0])
        """
    )
    result = pytester.runpytest("-p", "rigsim.pytest_plugin", "--rigsimd", rigsimd)
    result.assert_outcomes(passed=2)


def test_a_failed_test_gets_the_wire_log_of_the_devices_it_used(pytester, request):
    rigsimd = request.config.getoption("--rigsimd")
    pytester.makepyfile(
        """
        from fake_control import FakeControl
        from rigsim import ControlClient

        def test_fails(rigsim):
            rig = rigsim()
            rig.endpoint("tdc001")
            fake = FakeControl().__enter__()   # left running: the report reads it after the test
            rig.control = ControlClient(fake.url)
            rig.state("mcs0")
            assert False, "failing on purpose"
        """
    )
    result = pytester.runpytest("-p", "rigsim.pytest_plugin", "--rigsimd", rigsimd)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*rigsimd log (1)*", "*wire log tdc001 (1, last 200)*",
                                 "*(no wire log: 404*", "*wire log mcs0 (1, last 200)*",
                                 "*5.000 ms in  :GP0  ?3a4750300a?",
                                 "*note: sent while not referenced"])


def test_the_wire_log_of_the_real_daemon_is_attached(pytester, request):
    rigsimd = request.config.getoption("--rigsimd")
    pytester.makepyfile(
        """
        import socket
        def test_fails(rigsim):
            rig = rigsim()
            with socket.create_connection(rig.endpoint("mcs0").address, timeout=5) as s:
                s.sendall(b":GP0\\n")
                assert s.recv(100).startswith(b":P0,")
            assert False, "failing on purpose"
        """
    )
    result = pytester.runpytest("-p", "rigsim.pytest_plugin", "--rigsimd", rigsimd)
    result.assert_outcomes(failed=1)
    text = result.stdout.str()
    assert "wire log mcs0 (1, last 200)" in text
    assert ":GP0" in text


def test_a_session_daemon_is_shared_and_reset_between_tests(pytester, request):
    rigsimd = request.config.getoption("--rigsimd")
    pytester.makepyfile(
        """
        PIDS = []
        def test_first(rigsim_session):
            rig = rigsim_session()
            PIDS.append(rig.process.pid)
            rig.pause()
            rig.scale(3)
            assert rigsim_session() is rig and rig.clock()["paused"] is True   # not reset twice
        def test_second(rigsim_session):
            rig = rigsim_session()
            PIDS.append(rig.process.pid)
            clock = rig.clock()
            assert clock["paused"] is False and clock["time_scale"] == 1.0
        def test_third(rigsim_session):
            rig = rigsim_session({"devices": [{"name": "m", "protocol": "mcs", "model": "MCS-2D",
                "mcs": {"system_id": 1, "channels": [{"sensor_type": "S", "travel_nm": [-5000000, 5000000]},
                                                     {"sensor_type": "S", "travel_nm": [-5000000, 5000000]}]}}]})
            assert list(rig.endpoints) == ["m"] and rig.process.pid not in PIDS
            print("PIDS", PIDS)
        """
    )
    result = pytester.runpytest("-s", "-p", "rigsim.pytest_plugin", "--rigsimd", rigsimd)
    result.assert_outcomes(passed=3)
    line = [l for l in result.stdout.lines if l.startswith("PIDS") or "PIDS [" in l][0]
    pids = eval(line[line.index("["):])
    from rigsim import Rigsim
    with Rigsim(rigsimd=rigsimd) as probe:
        try:
            probe.reset()
            served = True
        except ControlError as e:
            served = e.status != 404
    if served:
        assert pids[0] == pids[1], "a session daemon was restarted although /api/reset is served"
    else:
        assert pids[0] != pids[1]   # no /api/reset yet: a fresh daemon per test


def test_a_failed_session_test_gets_only_its_part_of_the_daemon_log(pytester, request):
    rigsimd = request.config.getoption("--rigsimd")
    pytester.makepyfile(
        """
        def test_first(rigsim_session):
            rigsim_session()
        def test_fails(rigsim_session):
            rig = rigsim_session()
            rig.endpoint("mcs0")
            assert False, "failing on purpose"
        """
    )
    result = pytester.runpytest("-p", "rigsim.pytest_plugin", "--rigsimd", rigsimd)
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(["*rigsimd log (1)*", "*wire log mcs0 (1, last 200)*"])


def test_events_from_the_real_daemon(rigsim):
    """Rigsim.events() on the daemon's SSE stream: clock and fault events, filtered by device."""
    rig = rigsim()
    stream = rig.events(device="mcs0", timeout=5)
    try:
        # The stream is open once the daemon answered; the events below come after it.
        rig.pause()
        rig.inject("tdc001", "latency", latency_ms=1)   # another device's: filtered out
        fault = rig.inject("mcs0", "latency", latency_ms=1)
        seen = []
        for event in stream:
            seen.append(event)
            if event["type"] == "fault_added":
                break
        types = [e["type"] for e in seen]
        assert types[0] == "clock" and seen[0]["paused"] is True
        assert types[-1] == "fault_added"
        assert seen[-1]["device"] == "mcs0" and seen[-1]["id"] == fault
        assert all(e.get("device") in (None, "", "mcs0") for e in seen)
        assert [e["seq"] for e in seen] == sorted(e["seq"] for e in seen)
    finally:
        stream.close()


def test_pose_follows_a_stage_moved_over_tcp(rigsim):
    """Rigsim.pose() on the real daemon: the tip 20 mm above an MCS stage moved by a client."""
    rig = rigsim(os.path.join(os.path.dirname(__file__), "..", "..", "tests", "e2e", "kinematics_rig.json"))
    rig.pause()
    assert rig.pose("tip").position_mm == pytest.approx((0.5, 0, 50), abs=1e-9)
    stream = rig.events(type="frames", timeout=5)
    try:
        with socket.create_connection(rig.endpoint("stage").address, timeout=5) as s:
            assert mcs_ask(s, ":MPA0,-1000000,0") == ":E0,0"
            rig.run_until_idle(60_000)
        event = next(stream)
    finally:
        stream.close()
    assert event["type"] == "frames" and event["after"] == {"type": "move_ended", "device": "stage"}
    assert [f["name"] for f in event["frames"]] == ["x", "tip"]
    tip = rig.pose("tip")   # the counter started at 0 where the stage powered up (0.5 mm): -0.5 mm
    assert tip.position_mm == pytest.approx((-0.5, 0, 50), abs=1e-9)
    assert tip.parent == "x" and tip.tool is True and tip.joint is None
    assert tip.parent_relative.position_mm == pytest.approx((0, 0, 20))
    assert tip.quaternion == pytest.approx((1, 0, 0, 0)) and tip.rpy_deg == pytest.approx((0, 0, 0))
    assert rig.pose("x").joint == {"type": "prismatic", "device": "stage", "channel": 0, "position": pytest.approx(-0.5)}
    with pytest.raises(ControlError) as e:
        rig.pose("nope")
    assert e.value.status == 404
