#!/usr/bin/env python3
"""Write the man pages rigsimd(1), rigsimctl(1) and rigsim-rig(5) from the texts they document,
so that they say what --help and docs/config.md say (docs/packaging.md#man-pages):

  rigsimd(1)     from `rigsimd --help` and `rigsimd --version` (the usage text of emulator/main.cpp)
  rigsimctl(1)   from rigsimctl's argparse parser (python/rigsim/cli.py: build_parser), every
                 command's and action's help included
  rigsim-rig(5)  from docs/config.md (Markdown: headings, paragraphs, lists, tables, code blocks)

  scripts/make_man.py --rigsimd build/release/rigsimd            # writes docs/man/
  scripts/make_man.py --rigsimd build/release/rigsimd --check    # exit 1 and a diff if they drifted

The pages are committed (docs/man/), so they can be read without a build; CTest's man_pages test
runs --check, so a change to --help, rigsimctl or docs/config.md without the pages fails the suite.
Standard library only; the output depends on nothing but those sources (no date: the same sources
give the same bytes)."""

import argparse
import difflib
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MAN_DIR = os.path.join(ROOT, "docs", "man")


# ---- roff text ----

def escape(text):
    """Plain text for roff: backslashes and hyphens escaped, a leading dot or quote guarded."""
    text = text.replace("\\", "\\e").replace("-", "\\-")
    if text.startswith((".", "'")):
        text = "\\&" + text
    return text


def inline(markdown):
    """One line of Markdown inline text as roff: `code` and **strong** bold, *emphasis* italic,
    [text](link) as its text, HTML entities as their characters."""
    out = []
    pos = 0
    pattern = re.compile(r"`([^`]*)`|\*\*(.+?)\*\*|\[([^\]]*)\]\([^)]*\)|(?<![\w*])\*(?!\s)(.+?)(?<!\s)\*(?![\w*])")
    for m in pattern.finditer(markdown):
        out.append(escape(_entities(markdown[pos:m.start()])))
        if m.group(1) is not None:
            out.append("\\fB" + escape(m.group(1)) + "\\fR")
        elif m.group(2) is not None:
            out.append("\\fB" + inline(m.group(2)) + "\\fR")
        elif m.group(3) is not None:
            out.append(inline(m.group(3)))
        else:
            out.append("\\fI" + inline(m.group(4)) + "\\fR")
        pos = m.end()
    out.append(escape(_entities(markdown[pos:])))
    text = "".join(out)
    return text[2:] if text.startswith("\\&") and pos else text


def _entities(text):
    return text.replace("&lt;", "<").replace("&gt;", ">").replace("&amp;", "&")


def line(text):
    """A text line that roff does not take for a request."""
    return "\\&" + text if text.startswith((".", "'")) else text


def header(name, section, title):
    return [f'.TH {name.upper()} {section} "" "rigsim {version()}" "{title}"', ".SH NAME",
            ]


_VERSION = None


def version():
    return _VERSION


# ---- rigsimd(1): the usage text ----

def rigsimd_page(help_text):
    """rigsimd --help: the usage line, the description up to the first option, the options
    (two spaces, the flag, its text from column 25; a flag too long for its column on a line
    of its own), the closing paragraphs."""
    lines = help_text.rstrip("\n").split("\n")
    usage = lines[0]
    body = lines[1:]
    first_option = next(i for i, l in enumerate(body) if l.startswith("  --"))
    description = " ".join(l.strip() for l in body[:first_option] if l.strip())
    options = []   # (flag text, [text lines])
    i = first_option
    while i < len(body) and (body[i].startswith("  ") or not body[i].strip()):
        l = body[i]
        if not l.strip():
            i += 1
            if i < len(body) and not body[i].startswith("  "):
                break
            continue
        if l.startswith("  --"):
            flag, _, text = l[2:].partition("  ")
            options.append((flag.strip(), [text.strip()] if text.strip() else []))
        else:
            options[-1][1].append(l.strip())
        i += 1
    closing = [p for p in "\n".join(body[i:]).split("\n\n") if p.strip()]

    out = header("rigsimd", 1, "User Commands")
    out.append(escape("rigsimd - " + description.split(". ")[0].rstrip(".")))
    out += [".SH SYNOPSIS", "\\fBrigsimd\\fR " + escape(usage.split("rigsimd", 1)[1].strip())]
    out += [".SH DESCRIPTION", line(escape(description))]
    out.append(".SH OPTIONS")
    for flag, text in options:
        out += [".TP", "\\fB" + escape(flag) + "\\fR"]
        if text:
            out.append(line(escape(" ".join(text))))
    out.append(".SH NOTES")
    for paragraph in closing:
        out += [".PP", line(escape(" ".join(l.strip() for l in paragraph.split("\n"))))]
    out += [".SH FILES",
            ".TP", "\\fI/usr/share/rigsim/default.json\\fR",
            "the built-in default rig (compiled into rigsimd; this copy is for reading and editing)",
            ".TP", "\\fI/usr/share/rigsim/examples/\\fR, \\fI/usr/share/rigsim/stages/\\fR",
            "example rigs and the shipped stage descriptions",
            ".TP", "\\fI/etc/rigsim/NAME.json\\fR",
            "the rig that \\fBrigsim@NAME.service\\fR runs, its ptys in \\fI/run/rigsim/NAME/\\fR"]
    out += [".SH SEE ALSO", "\\fBrigsimctl\\fR(1), \\fBrigsim\\-rig\\fR(5); docs/cli.md and "
            "docs/control\\-api.md in the rigsim sources"]
    return "\n".join(out) + "\n"


# ---- rigsimctl(1): the argparse parser ----

def rigsimctl_page():
    sys.path.insert(0, os.path.join(ROOT, "python"))
    from rigsim.cli import build_parser   # noqa: E402  (the package of this tree)
    parser = build_parser()
    out = header("rigsimctl", 1, "User Commands")
    out.append(escape("rigsimctl - " + (parser.description or "").split("\n")[0].rstrip(".")))
    out += [".SH SYNOPSIS", ".nf", escape(_usage(parser)), ".fi"]
    # The flags every command takes (OPTIONS below), shown once: in a command's usage, "[OPTION]...".
    main_usage = _usage(parser)
    common = main_usage[len(parser.prog) + 1:main_usage.rindex(" COMMAND")]
    if parser.description:
        out += [".SH DESCRIPTION", line(escape(" ".join(parser.description.split())))]
    out.append(".SH OPTIONS")
    out += _options(parser)
    out.append(".SH COMMANDS")
    for name, sub, help_text in _subcommands(parser):
        out += [".SS " + escape(name), ".nf", escape(_usage(sub).replace(common, "[OPTION]...")), ".fi"]
        text = sub.description or help_text
        if text:
            out += [".PP", line(escape(" ".join(text.split())))]
        out += _options(sub, skip_common=True, parent=parser)
        for action_name, action, action_help in _subcommands(sub):
            out += [".TP", "\\fB" + escape(name + " " + action_name) + "\\fR",
                    line(escape(" ".join((action.description or action_help or "").split())))]
            usage = _usage(action).replace(common, "[OPTION]...")
            out += [".RS", ".nf", escape(usage), ".fi"]
            out += _options(action, skip_common=True, parent=parser)
            out.append(".RE")
    if parser.epilog:
        out += [".SH NOTES", line(escape(" ".join(parser.epilog.split())))]
    out += [".SH SEE ALSO", "\\fBrigsimd\\fR(1), \\fBrigsim\\-rig\\fR(5); docs/cli.md#rigsimctl and "
            "docs/control\\-api.md in the rigsim sources"]
    return "\n".join(out) + "\n"


def _usage(parser):
    text = parser.format_usage().strip()
    text = text[len("usage: "):] if text.startswith("usage: ") else text
    return " ".join(text.split())


def _subcommands(parser):
    for action in parser._actions:   # argparse has no public walk over sub-parsers
        if isinstance(action, argparse._SubParsersAction):
            helps = {a.dest: a.help for a in action._choices_actions}
            for name, sub in action.choices.items():
                yield name, sub, helps.get(name)


def _common_flags(parser):
    return {s for a in parser._actions for s in a.option_strings}


def _options(parser, skip_common=False, parent=None):
    common = _common_flags(parent) if skip_common and parent is not None else set()
    out = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction) or action.help == argparse.SUPPRESS:
            continue
        if action.option_strings and set(action.option_strings) <= common:
            continue
        if not action.option_strings and not action.help:
            continue   # named in the usage above; nothing more to say
        if action.option_strings:
            choices = "{" + ",".join(map(str, action.choices)) + "}" if action.choices else None
            metavar = "" if action.nargs == 0 else " " + (action.metavar or choices or action.dest.upper())
            tag = ", ".join("\\fB" + escape(s) + "\\fR" for s in action.option_strings) + escape(metavar)
        else:
            tag = "\\fI" + escape(action.metavar or action.dest) + "\\fR"
        help_text = (action.help or "")
        if "%(default)" in help_text:
            help_text = help_text % {"default": action.default}
        out += [".TP", tag, line(escape(" ".join(help_text.split())))]
    return out


# ---- rigsim-rig(5): docs/config.md ----

def rig_page(markdown):
    out = header("rigsim-rig", 5, "File Formats")
    out.append(escape("rigsim-rig - the rig file of rigsimd: controllers, channels, stages, kinematics (JSON)"))
    out += [".SH SYNOPSIS", "\\fBrigsimd \\-\\-config\\fR \\fIRIG.json\\fR",
            ".br", "\\fBrigsimd \\-\\-check\\-config\\fR \\fIRIG.json\\fR"]
    lines = markdown.split("\n")
    i = 0
    started = False
    paragraph = []

    def flush():
        if paragraph:
            out.extend([".PP", line(inline(" ".join(paragraph)))])
            paragraph.clear()

    while i < len(lines):
        l = lines[i]
        stripped = l.strip()
        if l.startswith("# "):
            out.append(".SH DESCRIPTION")
            started = True
            i += 1
            continue
        if not started:
            i += 1
            continue
        if stripped.startswith("```"):
            flush()
            i += 1
            out += [".sp", ".RS 4", ".nf"]
            while i < len(lines) and not lines[i].strip().startswith("```"):
                out.append(line(escape(lines[i])))
                i += 1
            out += [".fi", ".RE"]
            i += 1
            continue
        heading = re.match(r"^(#{2,6}) (.*)$", l)
        if heading:
            flush()
            level = len(heading.group(1))
            title = re.sub(r"\\f[BIR]", "", inline(heading.group(2)))
            out.append((".SH " + title.upper()) if level == 2 else (".SS " + title))
            i += 1
            continue
        if stripped.startswith("|"):
            flush()
            rows = []
            while i < len(lines) and lines[i].strip().startswith("|"):
                rows.append(_cells(lines[i]))
                i += 1
            out += _table(rows)
            continue
        item = re.match(r"^(\s*)(?:[-*]|\d+\.) (.*)$", l)
        if item:
            flush()
            text = [item.group(2)]
            i += 1
            while i < len(lines) and lines[i].startswith(" ") and lines[i].strip() \
                    and not re.match(r"^\s*(?:[-*]|\d+\.) ", lines[i]) and not lines[i].strip().startswith("```"):
                text.append(lines[i].strip())
                i += 1
            indent = 2 + len(item.group(1))
            out += [f".IP \\(bu {indent}", line(inline(" ".join(text)))]
            continue
        if not stripped:
            flush()
        else:
            paragraph.append(stripped)
        i += 1
    flush()
    out += [".SH SEE ALSO", "\\fBrigsimd\\fR(1), \\fBrigsimctl\\fR(1); docs/config.md in the rigsim sources, "
            "from which this page is made"]
    return "\n".join(out) + "\n"


def _cells(row):
    row = row.strip()
    if row.startswith("|"):
        row = row[1:]
    if row.endswith("|") and not row.endswith("\\|"):
        row = row[:-1]
    cells = re.split(r"(?<!\\)\|", row)
    return [c.strip().replace("\\|", "|") for c in cells]


def _table(rows):
    """A Markdown table as tagged paragraphs: the first cell the tag, each other cell a line
    "header: value" (the header row names them; a separator row is skipped)."""
    if len(rows) < 2:
        return []
    head = rows[0]
    body = [r for r in rows[1:] if not all(re.fullmatch(r":?-+:?", c or "-") for c in r)]
    out = []
    for row in body:
        out += [".TP", line(inline(row[0]) or "\\&")]
        parts = []
        for name, value in zip(head[1:], row[1:]):
            if value:
                parts.append(line(inline(name) + ": " + inline(value)))
        out += [p if k == 0 else ".br\n" + p for k, p in enumerate(parts)]
    return out


# ---- main ----

def pages(rigsimd):
    global _VERSION
    run = lambda *args: subprocess.run([rigsimd, *args], check=True, capture_output=True, text=True).stdout
    _VERSION = run("--version").strip().split()[-1]
    with open(os.path.join(ROOT, "docs", "config.md"), encoding="utf-8") as f:
        config = f.read()
    return {"rigsimd.1": rigsimd_page(run("--help")), "rigsimctl.1": rigsimctl_page(),
            "rigsim-rig.5": rig_page(config)}


def main(argv=None):
    parser = argparse.ArgumentParser(description="Write docs/man/ from --help and docs/config.md.")
    parser.add_argument("--rigsimd", required=True, help="the rigsimd whose --help makes rigsimd(1)")
    parser.add_argument("--check", action="store_true",
                        help="write nothing; exit 1 with a diff if a page in docs/man/ differs")
    parser.add_argument("--out", default=MAN_DIR, help="directory to write (default docs/man)")
    args = parser.parse_args(argv)
    drifted = False
    for name, text in pages(args.rigsimd).items():
        path = os.path.join(args.out, name)
        old = open(path, encoding="utf-8").read() if os.path.exists(path) else ""
        if args.check:
            if old != text:
                drifted = True
                sys.stdout.writelines(difflib.unified_diff(
                    old.splitlines(True), text.splitlines(True), f"docs/man/{name} (committed)",
                    f"docs/man/{name} (from the sources)", n=1))
        elif old != text:
            os.makedirs(args.out, exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
            print(f"wrote {path}")
    if drifted:
        print("make_man.py: the man pages drifted from --help, rigsimctl or docs/config.md: "
              "run scripts/make_man.py --rigsimd BUILD/rigsimd and commit docs/man/", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
