"""The README's first-contact snippets, run as a newcomer would paste them, against the default
rig (its TCP ports replaced by the ephemeral ones of a test daemon), with what they print checked
against the comments beside them."""

import contextlib
import io
import os
import re

README = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "README.md")


def python_blocks():
    with open(README, encoding="utf-8") as f:
        text = f.read()
    return re.findall(r"```python\n(.*?)```", text, re.S)


def run_snippet(code, rig):
    """Runs `code` with the default rig's fixed ports (40100.. in the README) replaced by the
    test daemon's; returns what it printed."""
    fixed = {40100: "mcs0", 40102: "kdc101", 55551: "mcs2"}
    for port, name in fixed.items():
        code = code.replace(f'("127.0.0.1", {port})', repr(rig.endpoint(name).address))
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README.md", "exec"), {"__name__": "readme"})
    return out.getvalue().splitlines()


def test_the_readme_has_an_mcs_an_apt_and_an_mcs2_snippet():
    blocks = python_blocks()
    assert len(blocks) == 3
    assert "40100" in blocks[0] and "40102" in blocks[1] and "55551" in blocks[2]


def test_the_mcs_snippet_prints_what_its_comments_say(rigsim):
    rig = rigsim()
    lines = run_snippet(python_blocks()[0], rig)
    assert lines[:3] == [":GNC -> :N3", ":MPA0,2000000,0 -> :E0,0", ":GS0 -> :S0,4"]
    assert re.fullmatch(r":GP0 -> :P0,-?\d+", lines[3])


def test_the_apt_snippet_prints_what_its_comment_says(rigsim):
    rig = rigsim()
    assert run_snippet(python_blocks()[1], rig) == ["0x6 27000001 KDC101"]


def test_the_mcs2_snippet_prints_what_its_comments_say(rigsim):
    rig = rigsim()
    assert run_snippet(python_blocks()[2], rig) == ['"MCS2-00000001"; 3', '262243 0,"No Error"']
