"""The in-tree build backend (python/_backend/rigsim_build.py): a correct wheel, offline."""

import base64
import csv
import hashlib
import io
import os
import sys
import tarfile
import zipfile

import pytest

PYTHON_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(PYTHON_DIR, "_backend"))
import rigsim_build  # noqa: E402


def test_the_backend_needs_nothing():
    assert rigsim_build.get_requires_for_build_wheel() == []
    assert rigsim_build.get_requires_for_build_sdist() == []
    assert rigsim_build.get_requires_for_build_editable() == []


def test_the_fallback_toml_parser_agrees_with_tomllib():
    tomllib = pytest.importorskip("tomllib")
    with open(os.path.join(PYTHON_DIR, "pyproject.toml"), "rb") as f:
        expected = tomllib.load(f)
    with open(os.path.join(PYTHON_DIR, "pyproject.toml"), encoding="utf-8") as f:
        assert rigsim_build._parse_simple_toml(f.read()) == expected


def test_the_wheel_holds_the_package_metadata_entry_points_and_a_correct_record(tmp_path):
    name = rigsim_build.build_wheel(str(tmp_path))
    assert name == "rigsim-0.1.0-py3-none-any.whl"
    with zipfile.ZipFile(tmp_path / name) as wheel:
        names = wheel.namelist()
        for module in ("__init__", "cli", "control", "daemon", "modem_lines", "pytest_plugin"):
            assert f"rigsim/{module}.py" in names
        assert "rigsim/py.typed" in names   # PEP 561: a user's mypy reads the package's hints
        assert not [n for n in names if "__pycache__" in n or n.endswith(".pyc")]
        info = "rigsim-0.1.0.dist-info"
        metadata = wheel.read(f"{info}/METADATA").decode()
        assert "Name: rigsim\n" in metadata and "Version: 0.1.0\n" in metadata
        assert 'Requires-Dist: pyserial>=3.4; extra == "serial"' in metadata
        assert "Root-Is-Purelib: true" in wheel.read(f"{info}/WHEEL").decode()
        entry_points = wheel.read(f"{info}/entry_points.txt").decode()
        assert "[console_scripts]\nrigsimctl = rigsim.cli:main\n" in entry_points
        assert "[pytest11]\nrigsim.pytest_plugin = rigsim.pytest_plugin\n" in entry_points
        rows = list(csv.reader(io.StringIO(wheel.read(f"{info}/RECORD").decode())))
        assert sorted(r[0] for r in rows) == sorted(names)
        for path, digest, size in rows:
            if path == f"{info}/RECORD":
                assert digest == size == ""
                continue
            data = wheel.read(path)
            expected = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
            assert (digest, int(size)) == (f"sha256={expected}", len(data)), path


def test_the_same_sources_make_the_same_wheel(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    name = rigsim_build.build_wheel(str(tmp_path / "a"))
    rigsim_build.build_wheel(str(tmp_path / "b"))
    assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()


def test_the_sdist_holds_what_a_build_needs(tmp_path):
    name = rigsim_build.build_sdist(str(tmp_path))
    with tarfile.open(tmp_path / name) as sdist:
        names = sdist.getnames()
    for path in ("PKG-INFO", "pyproject.toml", "_backend/rigsim_build.py", "rigsim/cli.py", "rigsim/py.typed"):
        assert f"rigsim-0.1.0/{path}" in names


def test_the_editable_wheel_points_here(tmp_path):
    name = rigsim_build.build_editable(str(tmp_path))
    with zipfile.ZipFile(tmp_path / name) as wheel:
        assert wheel.read("_rigsim_editable.pth").decode().strip() == PYTHON_DIR
