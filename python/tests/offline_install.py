#!/usr/bin/python3
"""CTest python_offline_install: `pip install --no-index ./python` into a fresh venv, with no
network (pip finds no index and every proxy points at a closed port), then checks that
`import rigsim` loads the installed copy, that the `rigsimctl` console script answers --help,
and that pytest (Debian's, seen through --system-site-packages) loads the plugin by its
pytest11 entry point. Needs Debian's python3-venv (scripts/deps.sh). Usage:
offline_install.py [PYTHON_DIR] (default: the python/ directory this file is in)."""

import os
import subprocess
import sys
import tempfile

PYTHON = "/usr/bin/python3"


def run(cmd, env, cwd, what):
    result = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        sys.stderr.write(f"FAIL: {what}: {' '.join(cmd)} exited {result.returncode}\n"
                         f"{result.stdout}\n{result.stderr}\n")
        sys.exit(1)
    return result.stdout


def source_files(root):
    return sorted(os.path.relpath(os.path.join(d, n), root)
                  for d, dirs, names in os.walk(root) for n in names if "__pycache__" not in d)


def main():
    python_dir = os.path.abspath(sys.argv[1] if len(sys.argv) > 1
                                 else os.path.join(os.path.dirname(__file__), ".."))
    before = source_files(python_dir)
    with tempfile.TemporaryDirectory(prefix="rigsim-offline-install-") as tmp:
        env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "PIP_"))}
        env.update({"PIP_NO_INDEX": "1", "PIP_DISABLE_PIP_VERSION_CHECK": "1",
                    "PIP_NO_CACHE_DIR": "1", "PYTHONDONTWRITEBYTECODE": "1",
                    "http_proxy": "http://127.0.0.1:9", "https_proxy": "http://127.0.0.1:9",
                    "HTTP_PROXY": "http://127.0.0.1:9", "HTTPS_PROXY": "http://127.0.0.1:9"})
        venv = os.path.join(tmp, "venv")
        run([PYTHON, "-m", "venv", "--system-site-packages", venv], env, tmp,
            "python3 -m venv (install Debian's python3-venv)")
        bin_dir = os.path.join(venv, "bin")
        env["PATH"] = bin_dir + os.pathsep + env.get("PATH", "")
        run([os.path.join(bin_dir, "pip"), "install", "--no-index", python_dir], env, tmp,
            "pip install --no-index ./python")

        where = run([os.path.join(bin_dir, "python"), "-c", "import rigsim; print(rigsim.__file__)"],
                    env, tmp, "import rigsim").strip()
        if not where.startswith(venv):
            sys.exit(f"FAIL: import rigsim loaded {where}, not the copy installed in {venv}")

        usage = run([os.path.join(bin_dir, "rigsimctl"), "--help"], env, tmp, "rigsimctl --help")
        if not usage.startswith("usage: rigsimctl"):
            sys.exit(f"FAIL: rigsimctl --help printed:\n{usage}")

        eps = run([os.path.join(bin_dir, "python"), "-c",
                   "from importlib.metadata import entry_points\n"
                   "print([e.value for e in entry_points(group='pytest11') if e.name == 'rigsim'])"],
                  env, tmp, "the pytest11 entry point")
        if eps.strip() != "['rigsim.pytest_plugin']":
            sys.exit(f"FAIL: pytest11 entry point rigsim: {eps.strip()}, expected rigsim.pytest_plugin")

        # pytest loads the plugin by entry point alone (no -p): the fixtures and --rigsimd exist.
        with open(os.path.join(tmp, "test_plugin_loaded.py"), "w") as f:
            f.write("def test_fixtures(rigsim, rigsim_session, pytestconfig):\n"
                    "    assert callable(rigsim) and callable(rigsim_session)\n"
                    "    assert pytestconfig.getoption('--rigsimd') == '/nowhere/rigsimd'\n")
        run([os.path.join(bin_dir, "python"), "-m", "pytest", "-q", "-p", "no:cacheprovider",
             "--rigsimd", "/nowhere/rigsimd", "test_plugin_loaded.py"], env, tmp,
            "pytest with the plugin loaded by entry point")

    after = source_files(python_dir)
    if after != before:
        sys.exit(f"FAIL: pip install wrote into the source tree: {sorted(set(after) - set(before))}")
    print("PASS: pip install --no-index ./python; import rigsim, rigsimctl --help, pytest11 plugin")


if __name__ == "__main__":
    main()
