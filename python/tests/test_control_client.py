"""ControlClient and Rigsim's control methods against the fake control API (fake_control.py),
for the routes the contract defines; test_rigsim.py covers the real daemon."""

import threading
import time

import pytest

from fake_control import FakeControl
from rigsim import ControlClient, ControlError, NotIdle, Rigsim


@pytest.fixture
def fake():
    with FakeControl() as f:
        yield f


@pytest.fixture
def rig(fake):
    """A Rigsim wired to the fake API (no daemon started)."""
    r = Rigsim(rigsimd="/nonexistent/rigsimd")
    r.control = ControlClient(fake.url)
    return r


def test_state_reads_the_device(rig, fake):
    state = rig.state("mcs0")
    assert state["protocol"] == "mcs"
    assert [c["index"] for c in state["channels"]] == [0, 1, 2]
    assert fake.requests[-1] == ("GET", "/api/devices/mcs0", {})


def test_state_without_a_name_is_the_rig(rig):
    assert [d["name"] for d in rig.state()["devices"]] == ["mcs0", "apt0"]


def test_set_patches_the_channel(rig, fake):
    channel = rig.set("mcs0", 1, position_si=0.002, referenced=True)
    assert channel["position_si"] == 0.002 and channel["referenced"] is True
    assert fake.requests[-1] == ("PATCH", "/api/devices/mcs0/channels/1",
                                 {"position_si": 0.002, "referenced": True})


def test_set_an_unknown_key_raises_with_the_server_message(rig):
    with pytest.raises(ControlError) as e:
        rig.set("mcs0", 0, speed=1)
    assert e.value.status == 400 and "speed" in e.value.message


def test_inject_returns_the_id_and_faults_lists_it(rig, fake):
    fid = rig.inject("mcs0", "stall", channel=2, force_n=1.5)
    assert fake.requests[-1] == ("POST", "/api/faults",
                                 {"device": "mcs0", "kind": "stall", "channel": 2, "force_n": 1.5})
    assert [f["id"] for f in rig.faults()] == [fid]
    assert rig.clear_fault(fid) == {"id": fid, "removed": True}
    assert rig.faults() == []


def test_inject_without_a_channel_sends_none(rig, fake):
    rig.inject("apt0", "unplugged")
    assert fake.requests[-1][2] == {"device": "apt0", "kind": "unplugged"}


def test_clear_an_unknown_fault_raises_404(rig):
    with pytest.raises(ControlError) as e:
        rig.clear_fault(99)
    assert e.value.status == 404


def test_clear_faults_removes_all(rig):
    a = rig.inject("mcs0", "stall")
    b = rig.inject("apt0", "slip")
    assert rig.clear_faults() == {"removed": [a, b]}


def test_reset_sends_keep_saved_only_when_false(rig, fake):
    assert rig.reset()["reset"] == ["mcs0", "apt0"]
    assert fake.requests[-1] == ("POST", "/api/reset", {})
    rig.reset(keep_saved=False)
    assert fake.requests[-1] == ("POST", "/api/reset", {"keep_saved": False})


def test_log_by_name_is_the_wire_log_and_without_is_the_daemon_log(rig, fake):
    assert len(rig.log("mcs0")["entries"]) == 2
    assert rig.log("mcs0", last=1)["entries"][0]["seq"] == 2
    assert fake.requests[-1][1] == "/api/devices/mcs0/log?last=1"
    assert rig.log() == ""   # no daemon ran: its log is empty
    rig.clear_log("mcs0")
    assert rig.log("mcs0")["entries"] == []


def test_devices_used_are_remembered_in_order(rig):
    rig.state("apt0")
    rig.inject("mcs0", "stall")
    rig.log("apt0")
    assert rig.used == ["apt0", "mcs0"]


def test_events_are_parsed_and_filtered(rig, fake):
    def later():
        fake.wait_for_subscribers(1)   # events are only sent live: publish once the stream is open
        fake.publish("move_started", "apt0", channel=0)
        fake.publish("move_started", "mcs0", channel=1)
        fake.publish("move_ended", "mcs0", channel=1, outcome="reached")
    threading.Thread(target=later, daemon=True).start()
    stream = rig.events(device="mcs0", timeout=5)
    got = [next(stream), next(stream)]
    stream.close()
    assert [(e["type"], e["device"], e["channel"]) for e in got] == [
        ("move_started", "mcs0", 1), ("move_ended", "mcs0", 1)]
    assert got[1]["outcome"] == "reached" and got[1]["seq"] == 3
    assert fake.requests[-1][1] == "/api/events?device=mcs0"


def test_events_end_after_the_timeout_without_one(rig):
    start = time.monotonic()
    assert list(rig.events(timeout=0.3)) == []
    assert time.monotonic() - start < 5


def test_events_on_an_unserved_route_raise(fake):
    client = ControlClient(fake.url + "/nothing")
    with pytest.raises(ControlError) as e:
        client.events()
    assert e.value.status == 404


def test_events_over_chunked_transfer_encoding_split_anywhere():
    """An HTTP/1.1 server may send the stream chunked, with chunk borders inside lines."""
    import socket
    stream = (b"event: move_started\nid: 7\ndata: {\"seq\":7,\"type\":\"move_started\",\"device\":\"a\"}\n\n"
              b": keep-alive\n\nevent: move_ended\nid: 8\ndata: {\"device\":\"a\",\n"
              b"data: \"outcome\":\"reached\"}\n\n")
    listener = socket.create_server(("127.0.0.1", 0))

    def serve():
        conn, _ = listener.accept()
        with conn:
            conn.recv(4096)
            conn.sendall(b"HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\n"
                         b"Transfer-Encoding: chunked\r\n\r\n")
            for i in range(0, len(stream), 13):
                piece = stream[i:i + 13]
                conn.sendall(b"%x\r\n%s\r\n" % (len(piece), piece))
            conn.sendall(b"0\r\n\r\n")
    threading.Thread(target=serve, daemon=True).start()
    client = ControlClient(f"http://127.0.0.1:{listener.getsockname()[1]}")
    events = list(client.events(timeout=5))
    listener.close()
    assert events == [{"seq": 7, "type": "move_started", "device": "a"},
                      {"device": "a", "outcome": "reached", "type": "move_ended", "seq": 8}]


# ---- frames ----

def test_frames_is_the_route_answer(rig, fake):
    frames = rig.frames()
    assert [f["name"] for f in frames["frames"]] == ["table", "rot", "x"]
    assert [t["name"] for t in frames["tools"]] == ["sample"]
    assert frames["collisions"] == [{"frames": ["x", "rot"]}]
    assert fake.requests[-1] == ("GET", "/api/frames", {})


def test_pose_gives_world_and_parent_relative_placements(rig, fake):
    pose = rig.pose("sample")
    assert fake.requests[-1] == ("GET", "/api/frames/sample", {})
    assert (pose.name, pose.parent, pose.tool, pose.joint) == ("sample", "x", True, None)
    assert pose.position_mm == (0.0, 2.0, 90.0)
    assert pose.quaternion == pytest.approx((0.5 ** 0.5, 0.0, 0.0, 0.5 ** 0.5))
    assert pose.rpy_deg == (0.0, 0.0, 90.0)
    assert pose.world.position_mm == pose.position_mm
    assert pose.parent_relative.position_mm == (0.0, 0.0, 40.0)
    assert pose.parent_relative.quaternion == (1.0, 0.0, 0.0, 0.0)
    joint = rig.pose("x").joint
    assert (joint["type"], joint["device"], joint["channel"], joint["position"]) == ("prismatic", "mcs0", 0, 2.0)


def test_pose_of_an_unknown_frame_raises_404(rig):
    with pytest.raises(ControlError) as e:
        rig.pose("nope")
    assert e.value.status == 404 and e.value.message == 'no frame named "nope"'


def test_a_pose_name_is_quoted_in_the_path(fake):
    with pytest.raises(ControlError):
        ControlClient(fake.url).pose("a b/c")
    assert fake.requests[-1][1] == "/api/frames/a%20b%2Fc"


def test_events_filtered_by_type(rig, fake):
    def later():
        fake.wait_for_subscribers(1)
        fake.publish("move_ended", "mcs0", channel=0, outcome="completed")
        fake.publish("frames", None, frames=[{"name": "x"}])
    threading.Thread(target=later, daemon=True).start()
    stream = rig.events(type="frames", timeout=5)
    got = next(stream)
    stream.close()
    assert got["type"] == "frames" and got["frames"] == [{"name": "x"}]
    assert fake.requests[-1][1] == "/api/events?type=frames"


def test_events_filtered_by_device_and_types(fake):
    stream = ControlClient(fake.url).events(device=["mcs0", "apt0"], type=["frames", "move_ended"], timeout=0.2)
    assert list(stream) == []
    assert fake.requests[-1][1] == "/api/events?device=mcs0,apt0&type=frames,move_ended"


def test_a_token_is_sent_as_a_bearer_header(fake, monkeypatch):
    monkeypatch.delenv("RIGSIM_CONTROL_TOKEN", raising=False)
    ControlClient(fake.url).clock()
    assert fake.headers[-1].get("Authorization") is None
    ControlClient(fake.url, token="t0k").pause()
    assert fake.headers[-1].get("Authorization") == "Bearer t0k"
    assert fake.headers[-1].get("Content-Type") == "application/json"
    monkeypatch.setenv("RIGSIM_CONTROL_TOKEN", "from-env")
    ControlClient(fake.url).clock()
    assert fake.headers[-1].get("Authorization") == "Bearer from-env"
    events = ControlClient(fake.url).events(timeout=0.2)
    list(events)
    assert fake.headers[-1].get("Authorization") == "Bearer from-env"
    ControlClient(fake.url, token="").clock()   # an explicit empty token: none sent
    assert fake.headers[-1].get("Authorization") is None


def test_run_until_idle_raises_not_idle_when_max_ms_comes_first(rig, fake):
    fake.busy_ms = 5000
    with pytest.raises(NotIdle, match="still busy after 1000 ms") as e:
        rig.run_until_idle(1000)
    assert e.value.clock["idle"] is False
    assert e.value.clock["reached_ms"] == 1000
    answer = rig.run_until_idle(1000, check=False)
    assert answer["idle"] is False
    assert rig.run_until_idle(600_000)["idle"] is True
    assert fake.requests[-1] == ("POST", "/api/clock", {"run_until_idle": True, "max_ms": 600000})


def test_run_until_idle_in_chunks_waits_for_the_drivers_message_between_them(rig, fake):
    fake.busy_ms = 2500
    fake.acks_on_poll = "apt0"
    answer = rig.run_until_idle(600_000, chunk_ms=1000, wait_for=("apt0", "MOT_ACK_DCSTATUSUPDATE"))
    assert answer["idle"] is True
    assert answer["reached_ms"] == 2500
    runs = [r[2] for r in fake.requests if r[:2] == ("POST", "/api/clock")]
    assert runs == [{"run_until_idle": True, "max_ms": 1000}] * 3
    polls = [r[1] for r in fake.requests if r[1] == "/api/devices/apt0/log"]
    assert len(polls) == 2   # one wait after each piece that left the rig busy
    with pytest.raises(ValueError, match="wait_for needs chunk_ms"):
        rig.run_until_idle(1000, wait_for=("apt0", "MOT_ACK_DCSTATUSUPDATE"))


def test_run_in_chunks_stops_at_max_ms_and_raises(rig, fake):
    fake.busy_ms = 10_000
    with pytest.raises(NotIdle):
        rig.run_until_idle(2500, chunk_ms=1000)
    runs = [r[2]["max_ms"] for r in fake.requests if r[:2] == ("POST", "/api/clock")]
    assert runs == [1000, 1000, 500]


def test_wait_for_message_finds_the_entry_or_times_out_naming_it(rig, fake):
    assert rig.log_cursor("mcs0") == 2
    entry = rig.wait_for_message("mcs0", "GP")
    assert entry["seq"] == 1
    with pytest.raises(TimeoutError, match="mcs0 received no GP within 0.05 s"):
        rig.wait_for_message("mcs0", "GP", after=1, timeout_s=0.05)
    with pytest.raises(TimeoutError):
        rig.wait_for_message("mcs0", "GP", direction="out", timeout_s=0.05)
    fake.acks_on_poll = "apt0"
    assert rig.wait_for_message("apt0", "MGMSG_MOT_ACK_DCSTATUSUPDATE", after=2)["seq"] == 3
    assert rig.wait_for_message("apt0", "MOT_ACK_DCSTATUSUPDATE", after=3)["seq"] == 4
