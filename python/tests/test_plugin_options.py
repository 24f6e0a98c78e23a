"""The pytest plugin's options and what a report gets, through pytester against the real rigsimd:
rigsimd and the ready rig from the ini file (relative to it, not to where pytest runs), logs
attached to a test that fails in setup, strict mode and assert_no_notes(), the rigsim_rig
fixture, the RTS/DTR shim's path, and the control client on HOST:PORT and on a device's port."""

import json
import os
import re
import socket

import pytest

from rigsim import ControlClient, NotControlApi, RigsimError, modem_lines_shim
from rigsim.daemon import modem_lines_preloaded

TWO_CHANNEL_MCS = {"devices": [{"name": "m", "protocol": "mcs", "model": "MCS-2D", "mcs": {
    "system_id": 7, "channels": [{"sensor_type": "S", "travel_nm": [-5000000, 5000000]},
                                 {"sensor_type": "S", "travel_nm": [-5000000, 5000000]}]}}]}


@pytest.fixture
def rigsimd(request):
    return os.path.abspath(request.config.getoption("--rigsimd"))


def run_inner(pytester, *args):
    return pytester.runpytest("-p", "rigsim.pytest_plugin", *args)


# ---- where rigsimd and the rig come from ----

def test_the_ini_key_rigsimd_is_relative_to_the_ini_file_not_to_where_pytest_runs(pytester, rigsimd, monkeypatch):
    (pytester.path / "bin").mkdir()
    os.symlink(rigsimd, pytester.path / "bin" / "rigsimd")
    pytester.makeini("[pytest]\nrigsimd = bin/rigsimd\n")
    sub = pytester.path / "tests"
    sub.mkdir()
    (sub / "test_it.py").write_text("def test_default_rig(rigsim):\n    assert 'mcs0' in rigsim().endpoints\n")
    monkeypatch.chdir(sub)   # bin/rigsimd is not here: only the ini file's directory has it
    result = run_inner(pytester, ".")
    result.assert_outcomes(passed=1)


def test_the_rigsimd_option_is_relative_to_where_pytest_runs(pytester, rigsimd, monkeypatch):
    pytester.makepyfile("def test_default_rig(rigsim):\n    assert 'mcs0' in rigsim().endpoints\n")
    relative = os.path.relpath(rigsimd, pytester.path)
    result = run_inner(pytester, f"--rigsimd={relative}")
    result.assert_outcomes(passed=1)


def test_rigsim_rig_from_the_command_line(pytester, rigsimd, tmp_path):
    rig = tmp_path / "two.json"
    rig.write_text(json.dumps(TWO_CHANNEL_MCS))
    pytester.makepyfile(
        """
        def test_first(rigsim_rig):
            assert list(rigsim_rig.endpoints) == ["m"]
            rigsim_rig.pause()
        def test_second_is_the_same_daemon_reset(rigsim_rig):
            assert list(rigsim_rig.endpoints) == ["m"]
            assert rigsim_rig.clock()["paused"] is False
        """
    )
    result = run_inner(pytester, f"--rigsimd={rigsimd}", f"--rigsim-rig={rig}")
    result.assert_outcomes(passed=2)


def test_rigsim_rig_from_the_ini_file_relative_to_it(pytester, rigsimd, monkeypatch):
    (pytester.path / "rigs").mkdir()
    (pytester.path / "rigs" / "two.json").write_text(json.dumps(TWO_CHANNEL_MCS))
    pytester.makeini(f"[pytest]\nrigsimd = {rigsimd}\nrigsim_rig = rigs/two.json\n")
    sub = pytester.path / "tests"
    sub.mkdir()
    (sub / "test_it.py").write_text("def test_rig(rigsim_rig):\n    assert list(rigsim_rig.endpoints) == ['m']\n")
    monkeypatch.chdir(sub)
    run_inner(pytester, ".").assert_outcomes(passed=1)


def test_rigsim_rig_without_a_rig_is_the_default_rig(pytester, rigsimd):
    pytester.makepyfile("def test_rig(rigsim_rig):\n    assert 'kdc101' in rigsim_rig.endpoints\n")
    run_inner(pytester, f"--rigsimd={rigsimd}").assert_outcomes(passed=1)


# ---- what a failed test's report gets ----

def test_a_fixture_that_fails_in_setup_gets_the_logs_attached(pytester, rigsimd):
    pytester.makepyfile(
        """
        import socket
        import pytest

        @pytest.fixture
        def homed(rigsim):
            rig = rigsim()
            with socket.create_connection(rig.endpoint("mcs0").address, timeout=5) as s:
                s.sendall(b":GP0\\n")
                assert s.recv(100).startswith(b":P0,")
            raise RuntimeError("the driver did not come up")

        def test_uses_it(homed):
            pass
        """
    )
    result = run_inner(pytester, f"--rigsimd={rigsimd}")
    result.assert_outcomes(errors=1)
    text = result.stdout.str()
    assert text.count("rigsimd log (1)") == 1 and "wire log mcs0 (1, last 200)" in text
    assert ":GP0" in text


def test_a_test_that_fails_in_its_body_gets_the_logs_once(pytester, rigsimd):
    pytester.makepyfile("def test_fails(rigsim):\n    rigsim().endpoint('mcs0')\n    assert False\n")
    result = run_inner(pytester, f"--rigsimd={rigsimd}")
    result.assert_outcomes(failed=1)
    assert result.stdout.str().count("rigsimd log (1)") == 1


# ---- strict mode ----

STRICT_SUITE = """
import socket
import pytest

def ask(rig, line):
    with socket.create_connection(rig.endpoint("mcs0").address, timeout=5) as s:
        s.sendall(line)
        return s.recv(100)

def test_clean(rigsim_session):
    assert ask(rigsim_session(), b":GNC\\n") == b":N3\\n"

def test_mistaken(rigsim_session):
    assert ask(rigsim_session(), b":GP7\\n") == b":E-1,7\\n"   # a channel the MCS-3D lacks

@pytest.mark.rigsim_strict(False)
def test_mistaken_but_allowed(rigsim_session):
    assert ask(rigsim_session(), b":GP7\\n") == b":E-1,7\\n"
"""


def test_without_strict_mode_a_noted_mistake_passes(pytester, rigsimd):
    pytester.makepyfile(STRICT_SUITE)
    run_inner(pytester, f"--rigsimd={rigsimd}").assert_outcomes(passed=3)


def test_strict_mode_from_the_ini_file_fails_a_test_whose_client_made_a_mistake(pytester, rigsimd):
    pytester.makeini(f"[pytest]\nrigsimd = {rigsimd}\nrigsim_strict = true\n")
    pytester.makepyfile(STRICT_SUITE)
    result = run_inner(pytester)
    result.assert_outcomes(passed=2, failed=1)
    result.stdout.fnmatch_lines(["*rigsim strict mode*rigsimd noted 1 client mistake(s):*"])
    text = result.stdout.str()
    assert re.search(r"mcs0 \d+\.\d{3} ms in GP7: answered with an error: E-1,7 Invalid Parameter Error", text)
    assert "wire log mcs0 (1, last 200)" in text   # the failed test's report has the wire log
    assert "FAILED test_strict_mode_from_the_ini_file_fails_a_test_whose_client_made_a_mistake.py::test_mistaken" \
        in result.stdout.lines


def test_strict_mode_from_the_command_line_and_per_test(pytester, rigsimd):
    pytester.makepyfile(STRICT_SUITE + """
@pytest.mark.rigsim_strict
def test_marked_strict(rigsim):
    assert ask(rigsim(), b":GP9\\n") == b":E-1,7\\n"
""")
    run_inner(pytester, f"--rigsimd={rigsimd}", "--rigsim-strict").assert_outcomes(passed=2, failed=2)
    run_inner(pytester, f"--rigsimd={rigsimd}").assert_outcomes(passed=3, failed=1)


def test_assert_no_notes_lists_each_noted_entry(rigsim):
    rig = rigsim()
    rig.assert_no_notes()
    with socket.create_connection(rig.endpoint("mcs0").address, timeout=5) as s:
        s.sendall(b":GP7\n")
        assert s.recv(100) == b":E-1,7\n"
    found = rig.notes()
    assert [(n.device, n.noted, len(n.entries)) for n in found] == [("mcs0", 1, 1)]
    assert rig.notes("kdc101") == []
    with pytest.raises(AssertionError, match=r"rigsimd noted 1 client mistake\(s\):\n  mcs0 \d+\.\d{3} ms in GP7: "
                                             r"answered with an error: E-1,7"):
        rig.assert_no_notes()
    rig.assert_no_notes(["kdc101", "tdc001"])   # only those devices
    rig.clear_log("mcs0")
    rig.assert_no_notes()


# ---- the RTS/DTR shim ----

def test_the_shim_is_found_beside_rigsimd(rigsimd, monkeypatch):
    monkeypatch.delenv("RIGSIM_MODEMLINES", raising=False)
    path = modem_lines_shim(rigsimd)
    assert path == os.path.join(os.path.dirname(os.path.realpath(rigsimd)), "librigsim_modemlines.so")
    assert os.path.isfile(path)


def test_the_shim_from_the_environment_and_a_missing_one(rigsimd, monkeypatch, tmp_path):
    shim = tmp_path / "librigsim_modemlines.so"
    shim.write_bytes(b"")
    monkeypatch.setenv("RIGSIM_MODEMLINES", str(shim))
    assert modem_lines_shim(rigsimd) == str(shim)
    monkeypatch.setenv("RIGSIM_MODEMLINES", str(tmp_path / "nope.so"))
    with pytest.raises(RigsimError, match="not a file"):
        modem_lines_shim(rigsimd)
    monkeypatch.delenv("RIGSIM_MODEMLINES")
    lonely = tmp_path / "bin" / "rigsimd"
    lonely.parent.mkdir()
    lonely.write_text("")
    with pytest.raises(RigsimError, match="librigsim_modemlines.so not found beside .*scripts/run.sh"):
        modem_lines_shim(str(lonely))


def test_the_shim_preloaded_in_a_child_is_seen_there(rigsimd, tmp_path):
    import subprocess
    import sys
    code = "from rigsim.daemon import modem_lines_preloaded; print(modem_lines_preloaded())"
    env = dict(os.environ, LD_PRELOAD=modem_lines_shim(rigsimd))
    assert subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                          check=True).stdout.strip() == "True"
    env.pop("LD_PRELOAD")
    assert subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                          check=True).stdout.strip() == "False"
    assert modem_lines_preloaded() in (True, False)


# ---- the control client's address ----

def test_the_control_client_takes_host_port(rigsim):
    rig = rigsim()
    bare = rig.control.url[len("http://"):]
    assert ControlClient(bare, token=rig.token).clock()["tick_hz"] == 1000


def test_the_control_client_on_a_device_port_says_so(rigsim):
    rig = rigsim()
    with pytest.raises(NotControlApi, match=r"answered ':E-1,.*\(a SmarAct MCS answer\), not HTTP"):
        ControlClient(rig.endpoint("mcs0").tcp).rig()
    with pytest.raises(NotControlApi, match=r"no HTTP answer from .* within 0.3 s") as silent:
        ControlClient(rig.endpoint("kdc101").tcp, timeout_s=0.3).rig()
    assert isinstance(silent.value, TimeoutError)   # as a timeout always was
    # the devices are none the worse for it
    with socket.create_connection(rig.endpoint("mcs0").address, timeout=5) as s:
        s.sendall(b":GNC\n")
        assert s.recv(100) == b":N3\n"


def test_the_control_client_ignores_the_environments_proxy(rigsim, monkeypatch):
    rig = rigsim()
    for name in ("http_proxy", "HTTP_PROXY", "all_proxy"):
        monkeypatch.setenv(name, "http://127.0.0.1:9")   # nothing listens there
    monkeypatch.delenv("no_proxy", raising=False)
    monkeypatch.delenv("NO_PROXY", raising=False)
    assert rig.clock()["tick_hz"] == 1000
    stream = rig.events(timeout=1)
    stream.close()
