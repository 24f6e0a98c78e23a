#!/usr/bin/python3
"""CTest python_offline_install: the rigsim package as a user installs and uses it.

`pip install --no-index ./python` into a fresh venv with no network (pip finds no index and
every proxy points at a closed port; Debian's pytest and pyserial are seen through
--system-site-packages), then, with nothing of the source tree on sys.path:
- `import rigsim` loads the installed copy, `rigsimctl --help` answers, the pytest11 entry point
  is named after the plugin's module;
- the installed copy holds py.typed, and a user's mypy (Debian's, through the venv) reads its
  hints: a wrong type in the user's code is an error;
- pytest loads the plugin by its entry point alone (the fixtures and options exist);
and with --rigsimd (the daemon under test), a driver-style suite (docs/examples with the config/
it reads: pyserial clients of an MCS and a KDC101 against the default rig, a threaded driver, a
piezo LUT, a kinematic chain) passes from the venv in each way the docs enable the plugin:
- by the entry point alone, rigsimd from `--rigsimd=PATH`;
- with `-p rigsim.pytest_plugin` (which used to fail with "Plugin already registered");
- with `pytest_plugins = ["rigsim.pytest_plugin"]` in the conftest, rigsimd from the ini key
  `rigsimd` relative to the project's pytest.ini, pytest started in a sub-directory;
- with the space form `--rigsimd PATH`, PATH outside the project and no test path given, pytest
  misses the project's ini file (the docs advise `--rigsimd=PATH`, which keeps it: both checked);
and `python -m rigsim.modem_lines` prints the RTS/DTR shim beside that rigsimd.
Needs Debian's python3-venv and python3-mypy (scripts/deps.sh --test). Usage:
offline_install.py [--rigsimd PATH] [--examples DIR] [PYTHON_DIR]
(PYTHON_DIR default: the python/ directory this file is in; DIR: docs/examples beside it)."""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile

PYTHON = "/usr/bin/python3"


def run(cmd, env, cwd, what, expect=0):
    result = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True, timeout=300)
    if (expect is not None and result.returncode != expect):
        sys.stderr.write(f"FAIL: {what}: {' '.join(cmd)} (in {cwd}) exited {result.returncode}, expected "
                         f"{expect}\n{result.stdout}\n{result.stderr}\n")
        sys.exit(1)
    return result


def source_files(root):
    return sorted(os.path.relpath(os.path.join(d, n), root)
                  for d, dirs, names in os.walk(root) for n in names if "__pycache__" not in d)


def suite_summary(result):
    """pytest -q's last line ("5 passed in 1.2s")."""
    lines = [line for line in result.stdout.splitlines() if line.strip()]
    return lines[-1] if lines else ""


def copy_suite(examples, dest):
    """docs/examples and the config/ they read rigs from (../../config), under `dest`; returns
    the copy of docs/examples."""
    suite = os.path.join(dest, "docs", "examples")
    shutil.copytree(examples, suite, ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    shutil.copytree(os.path.join(examples, "..", "..", "config"), os.path.join(dest, "config"))
    return suite


def make_project(tmp, examples, rigsimd):
    """A user's project: the example suite under docs/examples, a pytest.ini at its top naming
    rigsimd relative to itself (bin/rigsimd, a link to the daemon under test) and a top-level
    conftest.py that enables the plugin by pytest_plugins. Returns (project, the suite's
    directory)."""
    project = os.path.join(tmp, "project")
    suite = copy_suite(examples, project)
    os.makedirs(os.path.join(project, "bin"))
    os.symlink(rigsimd, os.path.join(project, "bin", "rigsimd"))
    with open(os.path.join(project, "pytest.ini"), "w") as f:
        f.write("[pytest]\nrigsimd = bin/rigsimd\n")
    # pytest takes pytest_plugins from the top-level conftest only (the rootdir's)
    with open(os.path.join(project, "conftest.py"), "w") as f:
        f.write('pytest_plugins = ["rigsim.pytest_plugin"]\n')
    return project, suite


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--rigsimd", default=None)
    parser.add_argument("--examples", default=None)
    parser.add_argument("python_dir", nargs="?", default=os.path.join(os.path.dirname(__file__), ".."))
    args = parser.parse_args()
    python_dir = os.path.abspath(args.python_dir)
    examples = os.path.abspath(args.examples or os.path.join(python_dir, "..", "docs", "examples"))
    rigsimd = os.path.abspath(args.rigsimd) if args.rigsimd else None
    before = source_files(python_dir)
    with tempfile.TemporaryDirectory(prefix="rigsim-offline-install-") as tmp:
        env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "PIP_", "RIGSIM"))}
        env.update({"PIP_NO_INDEX": "1", "PIP_DISABLE_PIP_VERSION_CHECK": "1",
                    "PIP_NO_CACHE_DIR": "1", "PYTHONDONTWRITEBYTECODE": "1",
                    "http_proxy": "http://127.0.0.1:9", "https_proxy": "http://127.0.0.1:9",
                    "HTTP_PROXY": "http://127.0.0.1:9", "HTTPS_PROXY": "http://127.0.0.1:9"})
        venv = os.path.join(tmp, "venv")
        run([PYTHON, "-m", "venv", "--system-site-packages", venv], env, tmp,
            "python3 -m venv (install Debian's python3-venv)")
        bin_dir = os.path.join(venv, "bin")
        python = os.path.join(bin_dir, "python")
        env["PATH"] = bin_dir + os.pathsep + env.get("PATH", "")
        run([os.path.join(bin_dir, "pip"), "install", "--no-index", python_dir], env, tmp,
            "pip install --no-index ./python")

        where = run([python, "-c", "import rigsim; print(rigsim.__file__)"], env, tmp, "import rigsim").stdout.strip()
        if not where.startswith(venv):
            sys.exit(f"FAIL: import rigsim loaded {where}, not the copy installed in {venv}")

        usage = run([os.path.join(bin_dir, "rigsimctl"), "--help"], env, tmp, "rigsimctl --help").stdout
        if not usage.startswith("usage: rigsimctl"):
            sys.exit(f"FAIL: rigsimctl --help printed:\n{usage}")
        usage = run([os.path.join(bin_dir, "rigsim-replay"), "--help"], env, tmp, "rigsim-replay --help").stdout
        if not usage.startswith("usage: rigsim-replay"):
            sys.exit(f"FAIL: rigsim-replay --help printed:\n{usage}")

        eps = run([python, "-c",
                   "from importlib.metadata import entry_points\n"
                   "print([(e.name, e.value) for e in entry_points(group='pytest11') if e.value.startswith('rigsim')])"],
                  env, tmp, "the pytest11 entry point").stdout.strip()
        if eps != "[('rigsim.pytest_plugin', 'rigsim.pytest_plugin')]":
            sys.exit(f"FAIL: pytest11 entry points of rigsim: {eps}, expected the one named rigsim.pytest_plugin")

        check_types(tmp, env, python, where)

        # pytest loads the plugin by entry point alone (no -p): the fixtures and options exist.
        with open(os.path.join(tmp, "test_plugin_loaded.py"), "w") as f:
            f.write("def test_fixtures(rigsim, rigsim_session, rigsim_rig, pytestconfig):\n"
                    "    pass\n"
                    "def test_options(pytestconfig):\n"
                    "    assert pytestconfig.getoption('--rigsimd') == '/nowhere/rigsimd'\n"
                    "    assert pytestconfig.getini('rigsim_strict') is False\n")
        run([python, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--rigsimd=/nowhere/rigsimd",
             "test_plugin_loaded.py::test_options"], env, tmp, "pytest with the plugin loaded by entry point")
        print("PASS: pip install --no-index ./python; import rigsim, rigsimctl and rigsim-replay --help, pytest11 entry point, "
              "py.typed")
        if rigsimd is None:
            print("(no --rigsimd: the driver-style suite was not run)")
        else:
            run_suite(tmp, env, python, examples, rigsimd)

    after = source_files(python_dir)
    if after != before:
        sys.exit(f"FAIL: pip install wrote into the source tree: {sorted(set(after) - set(before))}")


def check_types(tmp, env, python, where):
    """PEP 561: the installed package (`where`: its __init__.py) holds py.typed, so mypy reads its
    hints instead of skipping it as an untyped package: a user's file that gives a ControlClient
    answer (a dict) to a str gets exactly that error."""
    marker = os.path.join(os.path.dirname(where), "py.typed")
    if not os.path.isfile(marker):
        sys.exit(f"FAIL: the installed package has no py.typed ({marker})")
    with open(os.path.join(tmp, "user_types.py"), "w") as f:
        f.write("from rigsim import ControlClient\n\nnow_ms: str = ControlClient().clock()\n")
    result = run([python, "-m", "mypy", "--strict", "--config-file=", "--cache-dir=/dev/null", "user_types.py"],
                 env, tmp, "mypy on a user's file (install Debian's python3-mypy: scripts/deps.sh --test)",
                 expect=1)
    lines = [line for line in result.stdout.splitlines() if ": error:" in line]
    if len(lines) != 1 or not lines[0].startswith("user_types.py:3: error: Incompatible types in assignment"):
        sys.exit(f"FAIL: mypy did not read the installed package's hints (expected one error, on line 3):\n"
                 f"{result.stdout}{result.stderr}")


def run_suite(tmp, env, python, examples, rigsimd):
    project, tests = make_project(tmp, examples, rigsimd)
    pytest = [python, "-m", "pytest", "-q", "-p", "no:cacheprovider"]
    elsewhere = os.path.join(tmp, "elsewhere")
    os.makedirs(elsewhere)
    plain = copy_suite(examples, os.path.join(tmp, "plain"))   # without the pytest_plugins line

    ways = [
        ("the entry point alone, --rigsimd=PATH", pytest + [f"--rigsimd={rigsimd}", plain], elsewhere),
        ("-p rigsim.pytest_plugin", pytest + ["-p", "rigsim.pytest_plugin", f"--rigsimd={rigsimd}", plain], elsewhere),
        ("pytest_plugins in the conftest, the ini key rigsimd relative to pytest.ini, from docs/examples/",
         pytest + ["."], tests),
    ]
    for what, cmd, cwd in ways:
        result = run(cmd, env, cwd, f"the example suite from the venv, {what}")
        print(f"PASS: the example suite from the venv, {what}: {suite_summary(result)}")

    # The space form with a daemon outside the project and no test path (the project's ini
    # file says what to collect): pytest looks for its ini file before it knows the plugin's
    # options, takes PATH for a test path, searches from PATH's directory, finds no ini file
    # there and settles on a rootdir above both, without the project's pytest.ini.
    collect = [python, "-m", "pytest", "-p", "no:cacheprovider", "--co"]
    result = run(collect + ["--rigsimd", rigsimd], env, project, "collection with --rigsimd PATH", expect=None)
    if "configfile: pytest.ini" in result.stdout:
        sys.exit("FAIL: with the space form pytest found the project's pytest.ini: the docs' advice "
                 f"(write --rigsimd=PATH) may no longer be needed:\n{result.stdout}")
    result = run(collect + [f"--rigsimd={rigsimd}"], env, project, "collection with --rigsimd=PATH")
    if f"rootdir: {project}, configfile: pytest.ini" not in result.stdout:
        sys.exit(f"FAIL: with --rigsimd=PATH pytest did not find the project's pytest.ini:\n{result.stdout}")
    print("PASS: --rigsimd=PATH keeps the project's pytest.ini, --rigsimd PATH loses it (as docs/python.md says)")

    shim = run([python, "-m", "rigsim.modem_lines", f"--rigsimd={rigsimd}"], env, tmp,
               "python -m rigsim.modem_lines").stdout.strip()
    expected = os.path.join(os.path.dirname(os.path.realpath(rigsimd)), "librigsim_modemlines.so")
    if shim != expected:
        sys.exit(f"FAIL: python -m rigsim.modem_lines printed {shim!r}, expected {expected!r}")
    print(f"PASS: python -m rigsim.modem_lines: {shim}")


if __name__ == "__main__":
    main()
