"""rigsimctl: every sub-command against the fake control API (fake_control.py), and against
the real daemon. $RIGSIMCTL names the launcher to run (default: the source tree's scripts/rigsimctl)."""

import io
import json
import os
import subprocess
import sys
import threading
import time

import pytest

from fake_control import FakeControl
from rigsim.cli import _default_hint, build_parser, control_url, main
from rigsim.control import DEFAULT_CONTROL, ControlClient

HERE = os.path.dirname(os.path.abspath(__file__))
LAUNCHER = os.environ.get("RIGSIMCTL") or os.path.join(HERE, "..", "..", "scripts", "rigsimctl")


@pytest.fixture
def fake():
    with FakeControl() as f:
        yield f


def ctl(url, *argv):
    """rigsimctl in-process: (exit status, standard output)."""
    out = io.StringIO()
    status = main(["--control", url, *argv], out=out)
    return status, out.getvalue()


def ctl_json(url, *argv):
    status, text = ctl(url, *argv)
    assert status == 0, text
    return json.loads(text)


def run_launcher(*argv, env=None, timeout=30):
    """The launcher as a user runs it: a separate process."""
    full_env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    full_env.pop("PYTHONPATH", None)   # the launcher must find the package itself
    full_env.update(env or {})
    return subprocess.run([sys.executable, LAUNCHER, *argv], capture_output=True, text=True,
                          env=full_env, timeout=timeout)


# ---- each sub-command against the fake ----

def test_rig(fake):
    assert [d["name"] for d in ctl_json(fake.url, "rig")["devices"]] == ["mcs0", "apt0"]


def test_rig_table(fake):
    status, text = ctl(fake.url, "--format", "table", "rig")
    assert status == 0
    lines = text.splitlines()
    assert lines[0].split() == ["name", "protocol", "model", "firmware", "tcp", "pty"]
    assert lines[1].split()[:4] == ["mcs0", "mcs", "MCS-3D", "1.2.44"]
    assert "now_ms" in text


def test_state(fake):
    assert ctl_json(fake.url, "state", "apt0")["model"] == "TDC001"
    status, text = ctl(fake.url, "state", "mcs0", "--format", "table")
    assert status == 0 and text.splitlines()[0].split()[:3] == ["ch", "kind", "position_si"]
    assert len(text.splitlines()) == 4


def test_state_table_shows_an_mcs2_channels_activity():
    from rigsim.cli import render_table
    channel = {"index": 0, "kind": "linear", "position_si": 0.001, "position_protocol": 1000000000,
               "moving": False, "referenced": True, "state": {"word": 262240, "activity": "holding"}}
    text = render_table("state", {"channels": [channel]})
    assert text.splitlines()[1].split()[-1] == "holding"


def test_set_parses_values_as_json(fake):
    channel = ctl_json(fake.url, "set", "mcs0", "2", "position_si=1e-3", "referenced=true",
                       "limit_switch=forward")
    assert channel["index"] == 2
    assert fake.requests[-1] == ("PATCH", "/api/devices/mcs0/channels/2",
                                 {"position_si": 0.001, "referenced": True, "limit_switch": "forward"})


def test_set_without_fields_is_an_error(fake, capsys):
    status, _ = ctl(fake.url, "set", "mcs0", "0")
    assert status == 1
    assert "key=value" in capsys.readouterr().err
    assert fake.requests == []


def test_set_bad_pair_is_an_error(fake, capsys):
    assert ctl(fake.url, "set", "mcs0", "0", "position_si")[0] == 1
    assert "expected key=value" in capsys.readouterr().err


@pytest.mark.parametrize("argv, body", [
    (["clock", "pause"], {"pause": True}),
    (["clock", "resume"], {"resume": True}),
    (["clock", "step", "100"], {"step_ms": 100}),
    (["clock", "scale", "2.5"], {"scale": 2.5}),
    (["clock", "run-until-idle", "--max-ms", "5000"], {"run_until_idle": True, "max_ms": 5000}),
    (["clock", "run-until-idle"], {"run_until_idle": True, "max_ms": 600000}),
])
def test_clock_actions(fake, argv, body):
    ctl_json(fake.url, *argv)
    assert fake.requests[-1] == ("POST", "/api/clock", body)


def test_clock_show_is_the_default(fake):
    assert ctl_json(fake.url, "clock")["tick_hz"] == 1000
    assert ctl_json(fake.url, "clock", "show")["tick_hz"] == 1000
    assert [r[0] for r in fake.requests] == ["GET", "GET"]


def test_fault_add_list_rm_clear(fake):
    fault = ctl_json(fake.url, "fault", "add", "mcs0", "drop_bytes", "--channel", "1",
                     "direction=in", "probability=0.5", "seed=7")
    assert fake.requests[-1] == ("POST", "/api/faults", {"device": "mcs0", "kind": "drop_bytes",
                                 "channel": 1, "direction": "in", "probability": 0.5, "seed": 7})
    assert [f["id"] for f in ctl_json(fake.url, "fault", "list")] == [fault["id"]]
    status, text = ctl(fake.url, "fault", "list", "--format", "table")
    assert text.splitlines()[1].split()[:4] == [str(fault["id"]), "mcs0", "1", "drop_bytes"]
    assert ctl_json(fake.url, "fault", "rm", str(fault["id"])) == {"id": fault["id"], "removed": True}
    ctl_json(fake.url, "fault", "add", "apt0", "stall")
    assert ctl_json(fake.url, "fault", "clear")["removed"] == [2]


def test_fault_rm_unknown_shows_the_server_error(fake, capsys):
    assert ctl(fake.url, "fault", "rm", "42")[0] == 1
    assert capsys.readouterr().err.strip() == "rigsimctl: 404: no fault 42"


def test_events_stream_json_lines(fake):
    def later():
        fake.wait_for_subscribers(1)   # events are only sent live: publish once the stream is open
        fake.publish("move_started", "apt0", channel=0)
        fake.publish("status", "mcs0", channel=0, status={"code": 4})
    threading.Thread(target=later, daemon=True).start()
    # --timeout: a missed event ends the stream (and fails the test) instead of hanging it
    status, text = ctl(fake.url, "events", "--device", "mcs0", "--count", "1", "--timeout", "5")
    assert status == 0
    assert [json.loads(line)["type"] for line in text.splitlines()] == ["status"]
    assert fake.requests[-1][1] == "/api/events?device=mcs0"


def test_events_streams_until_ctrl_c(fake):
    import signal
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    process = subprocess.Popen([sys.executable, LAUNCHER, "--control", fake.url, "events"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    deadline = time.monotonic() + 10
    while not fake.wait_for_subscribers(1, timeout_s=0.05):   # poll: the stream is open
        assert time.monotonic() < deadline and process.poll() is None, process.stderr.read()
    fake.publish("clock", None, paused=True)
    assert json.loads(process.stdout.readline())["type"] == "clock"
    process.send_signal(signal.SIGINT)
    out, err = process.communicate(timeout=10)
    assert process.returncode == 0 and err == ""


def test_events_timeout_ends_the_stream(fake):
    assert ctl(fake.url, "events", "--timeout", "0.2") == (0, "")


def test_reset(fake):
    assert ctl_json(fake.url, "reset")["reset"] == ["mcs0", "apt0"]
    assert fake.requests[-1][2] == {}
    ctl_json(fake.url, "reset", "--erase-saved")
    assert fake.requests[-1][2] == {"keep_saved": False}


def test_log(fake):
    assert len(ctl_json(fake.url, "log", "mcs0")["entries"]) == 2
    ctl_json(fake.url, "log", "mcs0", "--last", "1")
    assert fake.requests[-1][1] == "/api/devices/mcs0/log?last=1"
    status, text = ctl(fake.url, "--format", "table", "log", "mcs0")
    assert status == 0 and ":GP0" in text and "sent while not referenced" in text
    ctl_json(fake.url, "log", "mcs0", "--clear")
    assert fake.requests[-1][:2] == ("DELETE", "/api/devices/mcs0/log")


def test_frames(fake):
    answer = ctl_json(fake.url, "frames")
    assert [f["name"] for f in answer["frames"]] == ["table", "rot", "x"]
    assert fake.requests[-1][1] == "/api/frames"
    assert ctl_json(fake.url, "frames", "sample")["parent_relative"]["position_mm"] == [0.0, 0.0, 40.0]
    assert fake.requests[-1][1] == "/api/frames/sample"


def test_frames_table(fake):
    status, text = ctl(fake.url, "--format", "table", "frames")
    assert status == 0
    lines = text.splitlines()
    assert lines[0].split() == ["name", "parent", "joint", "x_mm", "y_mm", "z_mm", "roll_deg", "pitch_deg",
                                "yaw_deg"]
    assert lines[1].split() == ["table", "-", "fixed", "0.0000", "0.0000", "0.0000", "0.0000", "0.0000", "0.0000"]
    assert lines[2].split() == ["rot", "table", "revolute", "apt0/0", "=", "90.0000", "0.0000", "0.0000",
                                "50.0000", "0.0000", "0.0000", "90.0000"]
    assert lines[3].split()[:6] == ["x", "rot", "prismatic", "mcs0/0", "=", "2.0000"]
    assert lines[4].split() == ["sample", "x", "tool", "0.0000", "2.0000", "90.0000", "0.0000", "0.0000",
                                "90.0000"]
    assert lines[-1] == "collisions: x - rot"


def test_frame_table(fake):
    status, text = ctl(fake.url, "frames", "x", "--format", "table")
    assert status == 0
    lines = text.splitlines()
    assert lines[0] == "x (parent rot, prismatic mcs0/0 = 2.0000)"
    assert lines[1].split() == ["relative", "to", "x_mm", "y_mm", "z_mm", "qw", "qx", "qy", "qz", "roll_deg",
                                "pitch_deg", "yaw_deg"]
    assert lines[2].split() == ["world", "0.0000", "2.0000", "50.0000", "0.707107", "0.000000", "0.000000",
                                "0.707107", "0.0000", "0.0000", "90.0000"]
    assert lines[3].split() == ["parent", "2.0000", "0.0000", "0.0000", "1.000000", "0.000000", "0.000000",
                                "0.000000", "0.0000", "0.0000", "0.0000"]


def test_frames_unknown_shows_the_server_error(fake, capsys):
    assert ctl(fake.url, "frames", "nope")[0] == 1
    assert capsys.readouterr().err.strip() == 'rigsimctl: 404: no frame named "nope"'


def test_events_by_type(fake):
    def later():
        fake.wait_for_subscribers(1)
        fake.publish("move_ended", "mcs0", channel=0, outcome="completed")
        fake.publish("frames", None, frames=[])
    threading.Thread(target=later, daemon=True).start()
    status, text = ctl(fake.url, "events", "--type", "frames", "--count", "1", "--timeout", "5")
    assert status == 0
    assert [json.loads(line)["type"] for line in text.splitlines()] == ["frames"]
    assert fake.requests[-1][1] == "/api/events?type=frames"


def test_unknown_device_shows_the_server_error(fake, capsys):
    assert ctl(fake.url, "state", "nope")[0] == 1
    assert capsys.readouterr().err.strip() == 'rigsimctl: 404: no device "nope"'


# ---- finding the API, the launcher, --help ----

def test_control_from_the_endpoints_file(fake, tmp_path):
    path = tmp_path / "endpoints.json"
    path.write_text(json.dumps({"control": fake.url, "devices": []}))
    out = io.StringIO()
    assert main(["--endpoints", str(path), "clock"], out=out) == 0
    assert json.loads(out.getvalue())["tick_hz"] == 1000


def test_control_from_the_environment(fake, monkeypatch):
    monkeypatch.setenv("RIGSIM_CONTROL", fake.url)
    out = io.StringIO()
    assert main(["clock"], out=out) == 0


def test_without_an_address_the_default_rig_is_asked(monkeypatch):
    monkeypatch.delenv("RIGSIM_CONTROL", raising=False)
    args = build_parser().parse_args(["rig"])
    assert control_url(args) == "http://127.0.0.1:40200"   # config/default.json "control"
    assert "127.0.0.1:40200 is the default rig's" in _default_hint(control_url(args))
    assert _default_hint("http://127.0.0.1:1") == ""


def test_the_default_rig_serves_control_where_rigsimctl_looks():
    with open(os.path.join(HERE, "..", "..", "config", "default.json")) as f:
        rig = json.load(f)
    assert f"127.0.0.1:{rig['control']['port']}" == DEFAULT_CONTROL


@pytest.mark.parametrize("form", ["{host}:{port}", "http://{host}:{port}", "http://{host}:{port}/"])
def test_control_takes_host_port_as_rigsimd_does(fake, form):
    host, _, port = fake.url[len("http://"):].rpartition(":")
    assert ctl_json(form.format(host=host, port=port), "clock")["tick_hz"] == 1000


def test_host_port_forms_are_urls():
    assert control_url(build_parser().parse_args(["--control", "[::1]:8080", "rig"])) == "http://[::1]:8080"
    assert control_url(build_parser().parse_args(["--control", "127.0.0.1:0", "rig"])) == "http://127.0.0.1:0"


def test_an_endpoints_file_without_control_is_an_error(tmp_path, capsys):
    path = tmp_path / "endpoints.json"
    path.write_text(json.dumps({"devices": []}))
    assert main(["--endpoints", str(path), "rig"], out=io.StringIO()) == 1
    assert "names no control API" in capsys.readouterr().err


def test_an_unreachable_api_is_an_error(capsys):
    assert main(["--control", "http://127.0.0.1:1", "rig"], out=io.StringIO()) == 1
    assert "cannot reach the control API at http://127.0.0.1:1" in capsys.readouterr().err


def test_options_after_the_sub_command(fake):
    out = io.StringIO()
    assert main(["clock", "step", "5", "--control", fake.url], out=out) == 0
    assert fake.requests[-1] == ("POST", "/api/clock", {"step_ms": 5})


def test_the_launcher_runs_and_prints_json(fake):
    result = run_launcher("--control", fake.url, "fault", "list")
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout) == []


def test_the_launcher_reports_errors_on_stderr(fake):
    result = run_launcher("--control", fake.url, "state", "nope")
    assert result.returncode == 1 and result.stdout == ""
    assert result.stderr == 'rigsimctl: 404: no device "nope"\n'


def test_the_launcher_finds_the_package_in_the_install_layout(fake, tmp_path):
    """As `cmake --install` lays it out: bin/rigsimctl, lib/rigsim/python/rigsim/."""
    import shutil
    source = os.path.join(HERE, "..", "..", "scripts", "rigsimctl")
    (tmp_path / "bin").mkdir()
    shutil.copy2(source, tmp_path / "bin" / "rigsimctl")
    shutil.copytree(os.path.join(HERE, "..", "rigsim"), tmp_path / "lib" / "rigsim" / "python" / "rigsim",
                    ignore=shutil.ignore_patterns("__pycache__"))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    result = subprocess.run([str(tmp_path / "bin" / "rigsimctl"), "--control", fake.url, "clock"],
                            capture_output=True, text=True, env=env, cwd=str(tmp_path), timeout=30)
    assert result.returncode == 0, result.stderr
    assert json.loads(result.stdout)["tick_hz"] == 1000


@pytest.mark.parametrize("argv", [[], ["rig"], ["state"], ["set"], ["clock"], ["clock", "step"],
                                  ["clock", "run-until-idle"], ["fault"], ["fault", "add"],
                                  ["fault", "rm"], ["frames"], ["events"], ["reset"], ["log"]])
def test_help_per_sub_command(argv):
    result = run_launcher(*argv, "--help")
    assert result.returncode == 0, result.stderr
    assert result.stdout.startswith("usage: rigsimctl " + " ".join(argv))


# ---- against the real daemon ----

def launch(rig, *argv):
    """The launcher against the daemon, with the daemon's token in the environment."""
    return run_launcher(*argv, env={"RIGSIM_CONTROL_TOKEN": rig.token})


def real(rig, *argv):
    """rigsimctl against the daemon."""
    result = launch(rig, "--control", rig.control.url, *argv)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout) if result.stdout.strip() else None


def test_real_token_by_flag_file_or_environment(rigsim, tmp_path):
    rig = rigsim()
    refused = run_launcher("--control", rig.control.url, "clock", env={"RIGSIM_CONTROL_TOKEN": ""})
    assert refused.returncode == 1
    assert refused.stderr.startswith("rigsimctl: 401: no token")
    wrong = run_launcher("--control", rig.control.url, "--token", "nope", "clock")
    assert wrong.returncode == 1 and wrong.stderr.startswith("rigsimctl: 401: wrong token")
    by_flag = run_launcher("--control", rig.control.url, "--token", rig.token, "clock")
    assert by_flag.returncode == 0 and json.loads(by_flag.stdout)["tick_hz"] == 1000
    token_file = tmp_path / "token"
    token_file.write_text(rig.token + "\n")
    by_file = run_launcher("clock", "--control", rig.control.url, "--token-file", str(token_file))
    assert by_file.returncode == 0, by_file.stderr
    missing = run_launcher("--control", rig.control.url, "--token-file", str(tmp_path / "absent"), "clock")
    assert missing.returncode == 1 and "cannot read the token file" in missing.stderr


def test_real_rig_and_clock(rigsim):
    rig = rigsim()
    assert [d["name"] for d in real(rig, "rig")["devices"]] == list(rig.endpoints)
    assert real(rig, "clock", "pause")["paused"] is True
    before = real(rig, "clock")["now_ms"]
    assert real(rig, "clock", "step", "250")["now_ms"] == before + 250
    assert real(rig, "clock", "scale", "4")["time_scale"] == 4.0
    assert "reached_ms" in real(rig, "clock", "run-until-idle", "--max-ms", "1000")
    assert real(rig, "clock", "resume")["paused"] is False


def test_real_bad_clock_step_shows_the_daemon_error(rigsim):
    rig = rigsim()
    result = launch(rig, "--control", rig.control.url, "clock", "step", "-1")
    assert result.returncode == 1
    assert result.stderr.startswith("rigsimctl: 400: \"step_ms\"")


def test_real_endpoints_file(rigsim):
    rig = rigsim()
    result = launch(rig, "--endpoints", os.path.join(rig.dir, "endpoints.json"), "clock")
    assert result.returncode == 0 and json.loads(result.stdout)["tick_hz"] == 1000


def test_real_state_set_log(rigsim):
    rig = rigsim()
    assert real(rig, "state", "mcs0")["name"] == "mcs0"
    channel = real(rig, "set", "mcs0", "0", "position_si=0.001")
    assert abs(channel["position_si"] - 0.001) < 1e-9
    assert real(rig, "log", "mcs0", "--last", "5")["device"] == "mcs0"
    real(rig, "log", "mcs0", "--clear")


def test_real_faults(rigsim):
    """Link faults (core's own, whatever the device family serves)."""
    rig = rigsim()
    fault = real(rig, "fault", "add", "mcs0", "latency", "latency_ms=5")
    assert (fault["kind"], fault["device"], fault["params"]["latency_ms"]) == ("latency", "mcs0", 5)
    assert [f["id"] for f in real(rig, "fault", "list")] == [fault["id"]]
    assert real(rig, "fault", "rm", str(fault["id"]))["removed"] is True
    assert real(rig, "fault", "list") == []
    other = real(rig, "fault", "add", "tdc001", "drop_bytes", "direction=in", "probability=0.5", "seed=3")
    assert real(rig, "fault", "clear")["removed"] == [other["id"]]
    result = launch(rig, "--control", rig.control.url, "fault", "rm", str(other["id"]))
    assert result.returncode == 1 and result.stderr.startswith("rigsimctl: 404: ")


def test_real_device_fault(rigsim):
    rig = rigsim()
    assert real(rig, "fault", "add", "mcs0", "stall")["kind"] == "stall"


def test_real_reset_and_events(rigsim):
    rig = rigsim()
    assert "mcs0" in real(rig, "reset")["reset"]
    real(rig, "events", "--timeout", "0.3")


KINEMATICS_RIG = os.path.join(HERE, "..", "..", "tests", "e2e", "kinematics_rig.json")


def test_real_frames(rigsim):
    rig = rigsim(KINEMATICS_RIG)
    answer = real(rig, "frames")
    assert [f["name"] for f in answer["frames"]] == ["table", "turn", "x"]
    assert [t["name"] for t in answer["tools"]] == ["tip"]
    assert real(rig, "frames", "tip")["world"]["position_mm"] == pytest.approx([0.5, 0, 50], abs=1e-9)
    result = launch(rig, "--control", rig.control.url, "--format", "table", "frames")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].split()[:3] == ["name", "parent", "joint"]
    assert lines[3].split() == ["x", "turn", "prismatic", "stage/0", "=", "0.5000", "0.5000", "0.0000",
                                "30.0000", "0.0000", "0.0000", "0.0000"]
    assert lines[4].split()[:6] == ["tip", "x", "tool", "0.5000", "0.0000", "50.0000"]
    assert lines[-1] == "collisions: none"
    result = launch(rig, "--control", rig.control.url, "frames", "nope")
    assert result.returncode == 1 and result.stderr == 'rigsimctl: 404: no frame named "nope"\n'


# ---- pointed at a device's port ----

def _one_line_error(capsys, argv):
    status = main(argv, out=io.StringIO())
    err = capsys.readouterr().err
    assert status == 1
    assert "Traceback" not in err and err.count("\n") == 1, err
    return err


def test_real_an_mcs_device_port_is_named_in_one_line(rigsim, capsys):
    rig = rigsim()
    err = _one_line_error(capsys, ["--control", rig.endpoint("mcs0").tcp, "rig"])
    assert err.startswith(f"rigsimctl: {rig.endpoint('mcs0').tcp} answered ':E")
    assert "(a SmarAct MCS answer), not HTTP: that is a device's port, not the control API" in err


def test_real_an_apt_device_port_is_named_in_one_line(rigsim, capsys, monkeypatch):
    rig = rigsim()
    monkeypatch.setattr("rigsim.cli.ControlClient",
                        lambda url, token=None: ControlClient(url, timeout_s=0.5, token=token))
    err = _one_line_error(capsys, ["--control", rig.endpoint("tdc001").tcp, "rig"])
    assert err.startswith(f"rigsimctl: no HTTP answer from {rig.endpoint('tdc001').tcp} within 0.5 s: "
                          "is it a device's port (an APT device ignores HTTP)")


def test_the_launcher_pointed_at_a_device_port_prints_one_line(rigsim):
    rig = rigsim()
    result = run_launcher("--control", rig.endpoint("mcs0").tcp, "clock")
    assert result.returncode == 1
    assert result.stderr.count("\n") == 1 and "Traceback" not in result.stderr
    assert "that is a device's port" in result.stderr
