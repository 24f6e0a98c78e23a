"""A PEP 517 build backend for rigsim, standard library only, so that `pip install ./python`
works offline (pip's build isolation installs nothing: `requires = []`).

It builds a pure-Python wheel (py3-none-any) of the `rigsim` package with METADATA, WHEEL,
entry_points.txt (the rigsimctl console script, the pytest11 plugin) and RECORD (sha256 of
every file), an sdist, and a PEP 660 editable wheel (a .pth file naming this directory).
The metadata comes from pyproject.toml's [project] table."""

import base64
import hashlib
import io
import os
import tarfile
import time
import zipfile

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))   # python/
PACKAGE = "rigsim"
TAG = "py3-none-any"
# Zip entries get a fixed date (1980-01-01, the earliest a zip can hold): the same sources
# make the same wheel.
ZIP_DATE = (1980, 1, 1, 0, 0, 0)


# ---- pyproject.toml ----

def _load_pyproject():
    path = os.path.join(HERE, "pyproject.toml")
    try:
        import tomllib
    except ImportError:   # Python < 3.11: the subset pyproject.toml uses
        return _parse_simple_toml(open(path, encoding="utf-8").read())
    with open(path, "rb") as f:
        return tomllib.load(f)


def _parse_simple_toml(text):
    """[a.b] tables, key = "string" and key = ["string", ...] on one line, whole-line
    comments: the subset pyproject.toml uses."""
    import ast
    doc = {}
    table = doc
    for raw in text.splitlines():
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        if line.startswith("[") and line.endswith("]"):
            table = doc
            for part in line[1:-1].split("."):
                table = table.setdefault(part.strip(), {})
            continue
        key, _, value = line.partition("=")
        table[key.strip().strip('"')] = ast.literal_eval(value.strip())
    return doc


def _project():
    return _load_pyproject()["project"]


def _dist_name(project):
    return project["name"].replace("-", "_")


def _dist_info(project):
    return f"{_dist_name(project)}-{project['version']}.dist-info"


# ---- the metadata files ----

def _metadata(project):
    lines = ["Metadata-Version: 2.1", f"Name: {project['name']}", f"Version: {project['version']}"]
    if project.get("description"):
        lines.append(f"Summary: {project['description']}")
    if project.get("requires-python"):
        lines.append(f"Requires-Python: {project['requires-python']}")
    for requirement in project.get("dependencies", []):
        lines.append(f"Requires-Dist: {requirement}")
    for extra, requirements in project.get("optional-dependencies", {}).items():
        lines.append(f"Provides-Extra: {extra}")
        for requirement in requirements:
            lines.append(f'Requires-Dist: {requirement}; extra == "{extra}"')
    return "\n".join(lines) + "\n"


def _wheel_file():
    return f"Wheel-Version: 1.0\nGenerator: rigsim_build\nRoot-Is-Purelib: true\nTag: {TAG}\n"


def _entry_points(project):
    groups = {}
    if project.get("scripts"):
        groups["console_scripts"] = project["scripts"]
    groups.update(project.get("entry-points", {}))
    out = []
    for group, entries in groups.items():
        out.append(f"[{group}]")
        out.extend(f"{name} = {target}" for name, target in entries.items())
        out.append("")
    return "\n".join(out)


def _dist_info_files(project):
    info = _dist_info(project)
    return {f"{info}/METADATA": _metadata(project).encode(),
            f"{info}/WHEEL": _wheel_file().encode(),
            f"{info}/entry_points.txt": _entry_points(project).encode()}


def _package_files():
    """(path in the wheel, path on disk) of every file of the package but bytecode."""
    files = []
    root = os.path.join(HERE, PACKAGE)
    for directory, dirs, names in os.walk(root):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__")
        for name in sorted(names):
            if name.endswith((".pyc", ".pyo")):
                continue
            disk = os.path.join(directory, name)
            files.append((os.path.relpath(disk, HERE).replace(os.sep, "/"), disk))
    return files


# ---- writing a wheel ----

def _record_line(path, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return f"{path},sha256={digest},{len(data)}"


def _write_wheel(wheel_directory, project, contents):
    """contents: {path in the wheel: bytes}; adds the dist-info files and RECORD."""
    name = f"{_dist_name(project)}-{project['version']}-{TAG}.whl"
    contents = dict(contents)
    contents.update(_dist_info_files(project))
    record_path = f"{_dist_info(project)}/RECORD"
    record = [_record_line(path, data) for path, data in contents.items()]
    record.append(f"{record_path},,")
    contents[record_path] = ("\n".join(record) + "\n").encode()
    with zipfile.ZipFile(os.path.join(wheel_directory, name), "w", zipfile.ZIP_DEFLATED) as wheel:
        for path, data in contents.items():
            entry = zipfile.ZipInfo(path, ZIP_DATE)
            entry.external_attr = 0o644 << 16
            entry.compress_type = zipfile.ZIP_DEFLATED
            wheel.writestr(entry, data)
    return name


# ---- the PEP 517 / PEP 660 hooks ----

def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def get_requires_for_build_editable(config_settings=None):
    return []


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    project = _project()
    contents = {}
    for path, disk in _package_files():
        with open(disk, "rb") as f:
            contents[path] = f.read()
    return _write_wheel(wheel_directory, project, contents)


def build_editable(wheel_directory, config_settings=None, metadata_directory=None):
    project = _project()
    return _write_wheel(wheel_directory, project, {f"_{PACKAGE}_editable.pth": (HERE + "\n").encode()})


def build_sdist(sdist_directory, config_settings=None):
    project = _project()
    base = f"{_dist_name(project)}-{project['version']}"
    name = base + ".tar.gz"
    files = [("pyproject.toml", os.path.join(HERE, "pyproject.toml")),
             ("_backend/rigsim_build.py", os.path.abspath(__file__))] + _package_files()
    with tarfile.open(os.path.join(sdist_directory, name), "w:gz", format=tarfile.PAX_FORMAT) as tar:
        pkg_info = _metadata(project).encode()
        _add_bytes(tar, f"{base}/PKG-INFO", pkg_info)
        for path, disk in files:
            with open(disk, "rb") as f:
                _add_bytes(tar, f"{base}/{path}", f.read())
    return name


def _add_bytes(tar, path, data):
    info = tarfile.TarInfo(path)
    info.size = len(data)
    info.mode = 0o644
    info.mtime = int(time.time())
    tar.addfile(info, io.BytesIO(data))
