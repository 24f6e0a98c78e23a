#!/usr/bin/env python3
"""Seed corpus and dictionaries of the fuzz targets (tests/fuzz, docs/reliability.md).

  make_corpus.py --out DIR          write DIR/<target>/<seed> for every target, generated from the
                                    golden transcripts, the rigs, stage files and test inputs of the
                                    source tree (nothing of it is committed)
  make_corpus.py --dicts            rewrite tests/fuzz/*.dict from the sources
  make_corpus.py --check-dicts      fail unless mcs.dict holds every command of the MCS codec's
                                    table and apt.dict every message ID of messages.def

Python 3 standard library only. The session targets' stream format (FF escapes) is the one
tests/fuzz/fuzz_rig.hpp reads.
"""

import argparse
import hashlib
import json
import pathlib
import re
import sys

FUZZ_DIR = pathlib.Path(__file__).resolve().parent
MAX_ADVANCE_MS = 0xEFFF   # one FF hi lo escape (hi < F0)


# ---- Sources --------------------------------------------------------------------------------

def mcs_mnemonics(src):
    """Every command of the MCS codec's table (emulator/mcs/codec.cpp, kCommands)."""
    text = (src / "emulator/mcs/codec.cpp").read_text()
    table = text[text.index("kCommands[] = {"):]
    table = table[:table.index("\n};")]
    return re.findall(r'\{\{"([A-Z]+)",', table)


def apt_messages(src):
    """(name, id) of every message of emulator/apt/messages.def."""
    text = (src / "emulator/apt/messages.def").read_text()
    return [(m.group(1), int(m.group(2), 16))
            for m in re.finditer(r"^RIGSIM_APT_TABLE\w*\(\s*(\w+)\s*,\s*(0x[0-9A-Fa-f]+)", text, re.M)]


def config_keys(src):
    """The keys the config loaders name in their key tables (k...Keys{...} in emulator/)."""
    keys = set()
    for path in sorted((src / "emulator").rglob("*.cpp")):
        for table in re.findall(r"k\w*Keys\s*\{([^}]*)\}", path.read_text()):
            keys.update(re.findall(r'"([a-z_0-9]+)"', table))
    return keys


def json_files(src):
    """Every rig and stage file of the tree: the rig loader's and the stage loader's seeds."""
    patterns = ["config/*.json", "config/examples/*.json", "config/stages/*.json", "tests/e2e/*.json",
                "docs/examples/*.json", "tests/device/transcripts/*.json"]
    return [p for pattern in patterns for p in sorted(src.glob(pattern))]


def json_keys(value, out):
    if isinstance(value, dict):
        for k, v in value.items():
            out.add(k)
            json_keys(v, out)
    elif isinstance(value, list):
        for v in value:
            json_keys(v, out)


def minified(value):
    return json.dumps(value, separators=(",", ":"))


# ---- The session stream (fuzz_rig.hpp) ------------------------------------------------------------

def escaped(data):
    return data.replace(b"\xff", b"\xff\xff")


def advance(ms):
    out = b""
    while ms > 0:
        step = min(ms, MAX_ADVANCE_MS)
        out += bytes([0xFF, step >> 8, step & 0xFF])
        ms -= step
    return out


def select(session):
    return bytes([0xFF, 0xF0 + session])


def duration_ms(text):
    m = re.match(r"\s*(\d+)\s*(ms|s|ticks)?\s*$", text)
    if not m:
        raise ValueError("bad duration: " + text)
    n = int(m.group(1))
    return n * 1000 if m.group(2) == "s" else n


# ---- MCS transcripts (tests/device/transcripts/*.txt; format: test_mcs_transcripts.cpp) ----------

def mcs_transcripts(src):
    """(name, header, steps) of each transcript; a step is ('send', bytes) or ('advance', ms)."""
    out = []
    for path in sorted((src / "tests/device/transcripts").glob("*.txt")):
        header, steps, answers = b"", [], []
        for line in path.read_text().splitlines():
            if not line or line.startswith("#"):
                continue
            kind, rest = line[0], line[2:]
            if kind == "@":
                rig = json.loads((src / rest.split(" ", 1)[1]).read_text())
                header = minified(rig).encode()
            elif kind == ">":
                steps.append(("send", rest.encode() + b"\n"))
            elif kind == "<":
                answers.append(rest.encode() + b"\n")
            elif kind == "~":
                steps.append(("advance", duration_ms(rest)))
        out.append((path.stem, header, steps, answers))
    return out


# ---- APT transcripts (tests/device/apt/transcripts/*.txt; format: test_apt_transcripts.cpp) -------

def apt_device(spec, name):
    """The rig JSON device of an '@' line's spec: model [firmware=X] (stages... | {apt object})."""
    model, _, rest = spec.strip().partition(" ")
    device = {"name": name, "protocol": "apt", "model": model}
    rest = rest.strip()
    if rest.startswith("firmware="):
        firmware, _, rest = rest.partition(" ")
        device["firmware"] = firmware[len("firmware="):]
        rest = rest.strip()
    if rest.startswith("{"):
        device["apt"] = json.loads(rest)
    else:
        stages = rest.split()
        rack = model in ("BBD201", "BBD202", "BBD203", "BSC201", "BSC202", "BSC203", "BSC101", "BSC102", "BSC103")
        device["apt"] = {"bays": stages} if rack or len(stages) > 1 else {"stage": stages[0]}
    return device


def hex_bytes(text):
    tokens = text.split()
    repeat = 1
    if tokens and re.fullmatch(r"\d+x", tokens[0]):
        repeat = int(tokens[0][:-1])
        tokens = tokens[1:]
    return bytes(int(t, 16) for t in tokens) * repeat


def apt_transcripts(src):
    """(name, rig, steps, answers) of each world of each transcript ('@' starts a world)."""
    out = []
    for path in sorted((src / "tests/device/apt/transcripts").glob("*.txt")):
        world = None
        for line in path.read_text().splitlines():
            if not line.strip() or line.startswith("#"):
                continue
            if line.startswith("@+"):
                devices = world[1]["devices"]
                devices.append(apt_device(line[2:], "transcript%d" % (len(devices) + 1)))
            elif line.startswith("@"):
                world = ("%s_%d" % (path.stem, len(out)), {"devices": [apt_device(line[1:], "transcript")]}, [], [])
                out.append(world)
            elif line.startswith(">"):
                m = re.match(r">(\d?)\s*(.*)", line)
                session = int(m.group(1)) - 1 if m.group(1) else 0
                world[2].append(("send", session, hex_bytes(m.group(2))))
            elif line.startswith("<"):
                m = re.match(r"<\d?\s*(.*)", line)
                world[3].append(hex_bytes(m.group(1)))
            elif line.startswith("~"):
                world[2].append(("advance", None, duration_ms(line[1:].replace("s", " s").replace("m s", "ms"))))
    return out


# ---- Seeds -----------------------------------------------------------------------------------

class Corpus:
    def __init__(self, out):
        self.out = out
        self.counts = {}

    def add(self, target, data):
        folder = self.out / target
        folder.mkdir(parents=True, exist_ok=True)
        name = hashlib.sha1(data).hexdigest()
        path = folder / name
        if not path.exists():
            path.write_bytes(data)
            self.counts[target] = self.counts.get(target, 0) + 1


MCS_PROBE = b":GNC\n:GSI\n:GCM\n:MPA0,1000000,0\n" + advance(1000) + b":GP0\n:GS0\n"
MCS2_PROBE = (b":DEV:NOCH?\r\n:CHAN0:STAT?\r\n:CHAN0:MMOD 0;VEL 1000000000\r\n:MOVE0 1000000000\r\n" + advance(1000) +
              b":CHAN0:POS?;STAT?\r\n:SYST:ERR:COUN?\r\n")
APT_PROBE = bytes.fromhex("050000005001 430401005001") + advance(3000) + bytes.fromhex("900401005001 050000002101")


def session_stream(steps, with_sessions):
    stream, current = b"", 0
    for step in steps:
        if step[0] == "advance":
            stream += advance(step[-1])
            continue
        if with_sessions and step[1] != current:
            current = step[1]
            stream += select(current)
        stream += escaped(step[-1])
    return stream


def mcs_seeds(src, corpus):
    for name, header, steps, answers in mcs_transcripts(src):
        sends = [s for s in steps if s[0] == "send"]
        corpus.add("mcs_session", header + b"\n" + session_stream(steps, False))
        corpus.add("mcs_framer", b"\x00" + b"".join(s[1] for s in sends))
        corpus.add("mcs_framer", b"\x07" + b"".join(s[1] for s in sends) + b"".join(answers))
        for _, data in sends:
            corpus.add("mcs_session", header + b"\n" + escaped(data) + advance(500) + b":GS0\n")
            corpus.add("mcs_framer", b"\x00" + data)
        # The session so far, then each command: a command at every state the transcript reaches.
        for i in range(0, len(steps), max(1, len(steps) // 8)):
            corpus.add("mcs_session", header + b"\n" + session_stream(steps[:i], False))


def apt_seeds(src, corpus):
    for name, rig, steps, answers in apt_transcripts(src):
        header = minified(rig).encode()
        corpus.add("apt_session", header + b"\n" + session_stream(steps, True))
        sends = [s[2] for s in steps if s[0] == "send"]
        corpus.add("apt_framer", b"\x00" + b"".join(sends))
        corpus.add("apt_framer", b"\x05" + b"".join(sends) + b"".join(answers))
        for data in sends:
            corpus.add("apt_session", header + b"\n" + escaped(data) + advance(200))
            corpus.add("apt_framer", b"\x00" + data)
        for data in answers:
            corpus.add("apt_framer", b"\x00" + data)
        for i in range(0, len(steps), max(1, len(steps) // 8)):
            corpus.add("apt_session", header + b"\n" + session_stream(steps[:i], True))
        corpus.add("rig_config", json.dumps(rig, indent=2).encode())


def rig_seeds(src, corpus):
    for path in json_files(src):
        text = path.read_bytes()
        if path.parent.name == "stages":
            corpus.add("stage_file", path.name.encode() + b"\n" + text)
            continue
        corpus.add("rig_config", text)
        rig = json.loads(text)
        devices = rig.get("devices", [])
        if not 0 < len(devices) <= 4:
            continue
        # The rig under each session target, every device probed in its protocol.
        stream = b""
        for d, device in enumerate(devices):
            probe = {"mcs": MCS_PROBE, "mcs2": MCS2_PROBE}.get(device.get("protocol"), APT_PROBE)
            stream += select(d) + escaped(probe)
        if any(d.get("protocol") == "mcs2" for d in devices):
            target = "mcs2_session"
        elif any(d.get("protocol") == "mcs" for d in devices):
            target = "mcs_session"
        else:
            target = "apt_session"
        corpus.add(target, minified(rig).encode() + b"\n" + stream)


def state_seeds(src, corpus):
    """State files: the literal ones of the tests, and one per APT transcript made of the SET
    messages it sends (what a unit saves: its data packet by bay and ID, apt_eeprom.cpp)."""
    for path in [src / "tests/device/apt/test_apt_state_file.cpp", src / "tests/e2e/state_file_test.cpp"]:
        if path.exists():
            for literal in re.findall(r'R"\((\{.*?\})\)"', path.read_text(), re.S):
                corpus.add("state_file", literal.encode())
    names = {name for name, _ in apt_messages(src)}
    ids = {i: name for name, i in apt_messages(src)}
    for name, rig, steps, _ in apt_transcripts(src):
        entries = {}
        for step in steps:
            data = step[-1] if step[0] == "send" else b""
            if len(data) > 6 and data[4] & 0x80:
                mid = data[0] | data[1] << 8
                if "_SET_" in ids.get(mid, ""):
                    entries["0x%04x" % mid] = data[6:6 + (data[2] | data[3] << 8)].hex()
        if not entries:
            continue
        state = {"cube": {"bay0/" + k: v for k, v in entries.items()},
                 "kcube": {"bay0/" + k: v for k, v in entries.items()},
                 "rack": {"bay%d/%s" % (b, k): v for k, v in entries.items() for b in (0, 1)},
                 "piezo": {"bay0/" + k: v for k, v in entries.items()}}
        corpus.add("state_file", json.dumps(state).encode())
    assert names


CONTROL_DEVICES = ["xyz", "rot", "tpz", "tsg"]   # fuzz_control_api.cpp's rig


def http_request(method, target, body):
    body = body.encode()
    head = "%s %s HTTP/1.1\r\nHost: 127.0.0.1:40200\r\n" % (method, target)
    if body or method in ("POST", "PATCH", "PUT"):
        head += "Content-Type: application/json\r\nContent-Length: %d\r\n" % len(body)
    return head.encode() + b"\r\n" + body


def control_seeds(src, corpus):
    """The requests of the control API's unit tests, per test case in order (a keep-alive
    connection), on each device of the fuzz target's rig."""
    call = re.compile(r'(?:call|error_of|handle)\(\s*"(GET|POST|PATCH|PUT|DELETE)"\s*,\s*"([^"]*)"'
                      r'(?:\s*,\s*(?:R"\((.*?)\)"|"((?:[^"\\]|\\.)*)"))?', re.S)
    for path in sorted((src / "tests/unit/control").glob("test_control*.cpp")):
        for case in re.split(r"\nTEST_CASE\(", path.read_text())[1:]:
            requests = [(m.group(1), m.group(2), m.group(3) or m.group(4) or "") for m in call.finditer(case)]
            if not requests:
                continue
            for device in CONTROL_DEVICES:
                connection = b""
                for method, target, body in requests:
                    target = re.sub(r"/api/devices/[^/?]+", "/api/devices/" + device, target)
                    body = re.sub(r'"device"\s*:\s*"[^"]*"', '"device":"%s"' % device, body)
                    request = http_request(method, target, body)
                    corpus.add("control_api", request)
                    connection += request
                corpus.add("control_api", connection)


def mcs2_seeds(src, corpus):
    """The MCS2 messages the grammar's unit test quotes (the guide's examples among them): each
    alone and all of them as one stream, CR LF terminated."""
    path = src / "tests/unit/mcs2/test_mcs2_message.cpp"
    if not path.exists():
        return
    text = path.read_text()
    messages = [m.encode().decode("unicode_escape").encode("latin-1")
                for m in re.findall(r'(?:parse_message|error)\("((?:[^"\\]|\\.)*)"\)', text)]
    messages += [m.encode() for m in re.findall(r'R"\((.*?)\)"', text)]
    for m in messages:
        corpus.add("mcs2_message", b"\x00" + m + b"\r\n")
    corpus.add("mcs2_message", b"\x07" + b"\r\n".join(messages) + b"\n")


MCS2_CALL = re.compile(r'(?:send|ask|number)\("((?:[^"\\]|\\.)*)"\)|advance_ms\(([0-9\']+)\)')


def mcs2_session_seeds(src, corpus):
    """Each MCS2 device test case as a session stream on the fuzz target's default rig (an empty
    header line): its messages in order, CR LF terminated, and its clock advances."""
    for path in sorted((src / "tests/device/mcs2").glob("test_*.cpp")):
        for case in re.split(r"\nTEST_CASE\(", path.read_text())[1:]:
            stream = b""
            for m in MCS2_CALL.finditer(case):
                if m.group(2):
                    stream += advance(min(int(m.group(2).replace("'", "")), 60000))
                else:
                    stream += escaped(m.group(1).encode().decode("unicode_escape").encode("latin-1") + b"\r\n")
            if stream:
                corpus.add("mcs2_session", b"\n" + stream)


def tap_seeds(src, corpus):
    """The recorder: each MCS and APT transcript's sends and answers as chunks of both directions,
    under its protocol's first byte (0 apt, 1 mcs), and every MCS2 device test case's messages (2)."""
    def chunks(first, pieces):
        out = bytes([first])
        for direction, data in pieces:
            for k in range(0, len(data), 63):
                part = data[k:k + 63]
                out += bytes([(len(part) << 2) | direction]) + part
        return out
    for name, header, steps, answers in mcs_transcripts(src):
        sends = [(0, s[1]) for s in steps if s[0] == "send"]
        corpus.add("tap_recorder", chunks(1, sends + [(1, a) for a in answers]))
    for name, rig, steps, answers in apt_transcripts(src):
        sends = [(0, s[2]) for s in steps if s[0] == "send"]
        corpus.add("tap_recorder", chunks(0, sends + [(1, a) for a in answers]))
    for path in sorted((src / "tests/device/mcs2").glob("test_*.cpp")):
        for case in re.split(r"\nTEST_CASE\(", path.read_text())[1:]:
            lines = [m.group(1).encode().decode("unicode_escape").encode("latin-1") + b"\r\n"
                     for m in MCS2_CALL.finditer(case) if m.group(1)]
            if lines:
                corpus.add("tap_recorder", chunks(2, [(0, l) for l in lines]))


def rfc2217_seeds(src, corpus):
    """The RFC 2217 codec: pyserial's opening (its Telnet options, the port's settings, RTS/DTR,
    a modem state poll), then each MCS transcript's commands as Telnet data, and the byte strings
    of the codec's unit test."""
    iac = b"\xff"
    def sb(command, value):
        return iac + b"\xfa\x2c" + bytes([command]) + value.replace(iac, iac + iac) + iac + b"\xf0"
    opening = (iac + b"\xfd\x01" + iac + b"\xfb\x03" + iac + b"\xfd\x03" + iac + b"\xfd\x2c" + iac + b"\xfb\x2c"
               + sb(1, (115200).to_bytes(4, "big")) + sb(2, b"\x08") + sb(3, b"\x01") + sb(4, b"\x01")
               + sb(5, b"\x01") + sb(5, b"\x0b") + sb(5, b"\x08") + sb(7, b"") + sb(12, b"\x03"))
    corpus.add("rfc2217", b"\x00" + opening)
    for name, header, steps, answers in mcs_transcripts(src):
        data = b"".join(s[1] for s in steps if s[0] == "send")
        corpus.add("rfc2217", b"\x03" + opening + data.replace(iac, iac + iac))
    path = src / "tests/unit/transport/test_rfc2217.cpp"
    if path.exists():
        for m in re.findall(r'bytes\(\{([0-9, ]+)\}\)', path.read_text()):
            corpus.add("rfc2217", b"\x00" + bytes(int(v) for v in m.split(",") if v.strip()))


def write_corpus(src, out):
    corpus = Corpus(out)
    rfc2217_seeds(src, corpus)
    tap_seeds(src, corpus)
    mcs2_seeds(src, corpus)
    mcs2_session_seeds(src, corpus)
    mcs_seeds(src, corpus)
    apt_seeds(src, corpus)
    rig_seeds(src, corpus)
    state_seeds(src, corpus)
    control_seeds(src, corpus)
    for target in sorted(corpus.counts):
        print("%s: %d seeds" % (target, corpus.counts[target]))


# ---- Dictionaries ------------------------------------------------------------------------------

def dict_line(name, value):
    text = "".join(chr(b) if 0x20 <= b < 0x7F and chr(b) not in '"\\' else "\\x%02X" % b for b in value)
    return '%s="%s"' % (name, text)


def mcs_dict(src):
    lines = ["# MCS command mnemonics of emulator/mcs/codec.cpp (make_corpus.py --dicts)"]
    lines += [dict_line("cmd_" + m, m.encode()) for m in mcs_mnemonics(src)]
    lines += [dict_line("sep_" + n, v) for n, v in
              [("colon", b":"), ("newline", b"\n"), ("comma", b","), ("minus", b"-"), ("int_max", b"2147483647"),
               ("int_min", b"-2147483648"), ("uint_max", b"4294967295")]]
    return lines


def apt_dict(src):
    lines = ["# APT message IDs of emulator/apt/messages.def, little-endian (make_corpus.py --dicts)"]
    lines += [dict_line(name, bytes([i & 0xFF, i >> 8])) for name, i in apt_messages(src)]
    lines += [dict_line("addr_" + n, bytes([v])) for n, v in
              [("host", 0x01), ("rack", 0x11), ("bay0", 0x21), ("bay1", 0x22), ("bay2", 0x23), ("unit", 0x50),
               ("unit_data", 0xD0), ("bay0_data", 0xA1)]]
    return lines


def json_dict(src):
    keys = config_keys(src)
    for path in json_files(src):
        json_keys(json.loads(path.read_text()), keys)
    lines = ["# JSON syntax and every key of the rigs, stages and config loaders' tables (make_corpus.py --dicts)"]
    lines += [dict_line("tok_%d" % i, t.encode()) for i, t in
              enumerate(["{", "}", "[", "]", ":", ",", '"', "true", "false", "null", "-1", "0", "1e308", "-0",
                         "1e-9", "4294967296", "9223372036854775808", "\\u0000", "\\ud800"])]
    lines += [dict_line("key_" + k, ('"%s":' % k).encode()) for k in sorted(keys)]
    return lines


def http_dict(src):
    words = set()
    for path in sorted((src / "emulator/control").glob("*.cpp")):
        words.update(w for w in re.findall(r'"([a-z_]{2,})"', path.read_text()))
    lines = ["# HTTP tokens, the control API's routes and JSON keys (make_corpus.py --dicts)"]
    tokens = ["GET ", "POST ", "PATCH ", "PUT ", "DELETE ", " HTTP/1.1\r\n", " HTTP/1.0\r\n", "\r\n", "\r\n\r\n",
              "Host: 127.0.0.1\r\n", "Host: localhost:40200\r\n", "Host: rig.example\r\n", "Host: [::1]:40200\r\n",
              "Content-Type: application/json\r\n", "Content-Length: ", "Transfer-Encoding: chunked\r\n",
              "Connection: close\r\n", "Expect: 100-continue\r\n", "Origin: http://127.0.0.1:40200\r\n",
              "Sec-Fetch-Site: same-origin\r\n", "Sec-Fetch-Site: cross-site\r\n",
              "Authorization: Bearer fuzz-token\r\n", "/api/", "/api/rig", "/api/clock", "/api/devices/",
              "/channels/", "/api/faults", "/api/reset", "/api/events", "/api/frames", "/log", "/trace", "?", "&",
              "=", "%", "xyz", "rot", "tpz", "tsg", "/ui/app.js", "/ui/style.css"]
    lines += [dict_line("http_%d" % i, t.encode()) for i, t in enumerate(tokens)]
    lines += [dict_line("word_" + w, w.encode()) for w in sorted(words)]
    return lines


def mcs2_keywords(src):
    """Every keyword of emulator/mcs2/properties.cpp's paths, as (long form, short form, indexed)."""
    text = (src / "emulator/mcs2/properties.cpp").read_text()
    out = []
    for path in re.findall(r'Property\{Id::\w+, "([^"]+)"', text):
        for word in re.findall(r"[*:]?([A-Za-z]+#?)", path.replace("[", "").replace("]", "")):
            indexed = word.endswith("#")
            word = word.rstrip("#")
            entry = (word.upper(), "".join(c for c in word if c.isupper()) or word.upper(), indexed)
            if entry not in out:
                out.append(entry)
    return out


def mcs2_dict(src):
    lines = ["# MCS2 keywords of emulator/mcs2/properties.cpp, long and short forms (make_corpus.py --dicts)"]
    for long_form, short_form, indexed in mcs2_keywords(src):
        suffix = "0" if indexed else ""
        lines.append(dict_line("kw_" + long_form.lower(), (":" + long_form + suffix).encode()))
        if short_form != long_form:
            lines.append(dict_line("kw_" + long_form.lower() + "_short", (":" + short_form + suffix).encode()))
    lines += [dict_line("sep_" + n, v) for n, v in
              [("semicolon", b";"), ("query", b"?"), ("comma", b","), ("quote", b'"'), ("crlf", b"\r\n"),
               ("star", b"*"), ("space", b" "), ("minus_one", b"-1"), ("infinite", b"4294967295"),
               ("fraction", b".000000"), ("int64_max", b"9223372036854775807")]]
    return lines


DICTS = {"mcs.dict": mcs_dict, "apt.dict": apt_dict, "json.dict": json_dict, "http.dict": http_dict,
         "mcs2.dict": mcs2_dict}


def check_dicts(src):
    """mcs.dict holds every mnemonic of the codec's table; apt.dict every ID of messages.def; mcs2.dict
    every keyword of the MCS2 property table."""
    def values(name):
        out = set()
        for line in (FUZZ_DIR / name).read_text().splitlines():
            m = re.match(r'^\w+="(.*)"$', line)
            if m:
                out.add(re.sub(r"\\x([0-9A-Fa-f]{2})", lambda h: chr(int(h.group(1), 16)), m.group(1)).encode("latin-1"))
        return out
    missing = ["mcs.dict: " + m for m in mcs_mnemonics(src) if m.encode() not in values("mcs.dict")]
    apt = values("apt.dict")
    missing += ["apt.dict: %s (0x%04X)" % (n, i) for n, i in apt_messages(src) if bytes([i & 0xFF, i >> 8]) not in apt]
    mcs2 = values("mcs2.dict")
    missing += ["mcs2.dict: " + k for k, _, indexed in mcs2_keywords(src)
                if (":" + k + ("0" if indexed else "")).encode() not in mcs2]
    if len(mcs_mnemonics(src)) < 60 or len(apt_messages(src)) < 100 or len(mcs2_keywords(src)) < 100:
        missing.append("the tables were not found where make_corpus.py reads them")
    for m in missing:
        print("missing from " + m, file=sys.stderr)
    if missing:
        print("run tests/fuzz/make_corpus.py --dicts", file=sys.stderr)
        return 1
    print("mcs.dict: %d commands, apt.dict: %d messages, mcs2.dict: %d keywords: complete"
          % (len(mcs_mnemonics(src)), len(apt_messages(src)), len(mcs2_keywords(src))))
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--source", type=pathlib.Path, default=FUZZ_DIR.parent.parent, help="the source tree")
    parser.add_argument("--out", type=pathlib.Path, help="write the seed corpus here (one folder per target)")
    parser.add_argument("--dicts", action="store_true", help="rewrite tests/fuzz/*.dict from the sources")
    parser.add_argument("--check-dicts", action="store_true", help="check mcs.dict and apt.dict against the tables")
    args = parser.parse_args()
    src = args.source.resolve()
    if args.dicts:
        for name, make in DICTS.items():
            (FUZZ_DIR / name).write_text("\n".join(make(src)) + "\n")
    if args.out:
        write_corpus(src, args.out)
    if args.check_dicts:
        return check_dicts(src)
    if not (args.dicts or args.out):
        parser.error("nothing to do: --out DIR, --dicts or --check-dicts")
    return 0


if __name__ == "__main__":
    sys.exit(main())
