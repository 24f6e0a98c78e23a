#!/usr/bin/env python3
"""Per-unit coverage of the APT manual's "Message Cross Reference by Unit Part Number" tables.

Usage: scripts/apt_coverage.py [--manual PATH] [--check DOC] [SOURCE_DIR]

The manual (Thorlabs' "APT Communications Protocol", issue 3 of 2012, pp.131-138, as Markdown
text; not part of the repository, docs/protocol/apt.md says where to obtain it) is read from
--manual PATH, else $RIGSIM_APT_MANUAL. Without it, --check checks what the sources alone decide:
every message of messages.def has its row in DOC's per-message tables and no row names an ID
the table lacks, with each row's "kinds" cell as the sources give it; the per-unit table between
the markers is left as it is.

Reads the cross-reference tables (manual pp.131-138) from the manual's text, and what rigsim
does from its sources: the message IDs and the takes lists that name each message
(emulator/apt/messages.def), each model's kind, `takes` list (the one it names), rack flag and
fault report form (emulator/apt/catalogue.cpp), and the messages each module
class and the unit shell have a handler for (the MGMSG_ name in the `///` line of each `on()` in
module.hpp, apt_device.hpp, rack_modules.hpp and the kind's module header). A message of a
unit's table counts as implemented when the unit acts on it (host->unit: a handler, and the
model's `takes` list or the generic set) or sends it (unit->host: the answer to a request it
acts on, a GET of its `takes` list, or an unsolicited message of its kind).

Prints the Markdown table of docs/protocol/apt.md ("Coverage per unit"; needs the manual). With
--check DOC, exits 1 (and prints the difference) when DOC's tables differ from what the manual
and the sources give; --write DOC rewrites them. Standard library only. Exit 2 on unreadable
input or a bad argument, 77 when the table is asked for without a manual.
"""
import os
import re
import sys

BEGIN = "<!-- apt_coverage.py: begin -->"
END = "<!-- apt_coverage.py: end -->"
SKIP = 77   # no manual to print the per-unit table from

# The cross-reference table each emulated model is counted against (the K-Cubes take their
# T-Cube's table: the manual predates them), and the page it starts on.
TABLE_OF = {
    "TDC001": ("TDC001", 136), "KDC101": ("TDC001", 136),
    "TSC001": ("TSC001", 138), "KSC101": ("TSC001", 138),
    "TPZ001": ("TPZ001", 133), "KPZ101": ("TPZ001", 133),
    "BPC301": ("BPC30x Series", 132), "BPC303": ("BPC30x Series", 132),
    "TSG001": ("TSG001", 134), "KSG101": ("TSG001", 134),
}
ORDER = ["TDC001", "KDC101", "TST001", "KST101", "BSC203", "BBD203", "K10CR1", "LTS150", "LTS300", "KBD101",
         "MFF101", "MFF102", "MPC320", "MPC220", "KIM101", "TIM101", "TSC001", "KSC101",
         "TPZ001", "KPZ101", "BPC301", "BPC303", "MMR601", "TSG001", "KSG101"]

# The module header(s) of each kind (catalogue.hpp UnitKind; motors by MotorKind).
# kcube_params.hpp: the motor messages of later protocol issues, which every motor module hands to its
# KCubeParams (which model takes which: kcube_params.cpp).
KIND_HEADERS = {
    "DcServo": ["motor_module.hpp", "kcube_params.hpp"], "Stepper": ["motor_module.hpp", "kcube_params.hpp"],
    "Brushless": ["motor_module.hpp", "brushless_module.hpp", "kcube_params.hpp"],
    "Solenoid": ["solenoid_module.hpp"], "Piezo": ["piezo_module.hpp", "piezo_card.hpp"], "StrainGauge": ["strain_gauge_module.hpp"],
    "Flipper": ["flipper_module.hpp"], "Polariser": ["polariser_module.hpp"], "PiezoMotor": ["pzmot_module.hpp"],
}
# What a unit sends unprompted (docs/protocol/apt.md "Unsolicited messages", "Faults"): motor units
# their end-of-move messages and status updates; the others' updates are GETs of their takes list.
UNSOLICITED_MOTOR = ["MGMSG_MOT_MOVE_HOMED", "MGMSG_MOT_MOVE_COMPLETED", "MGMSG_MOT_MOVE_STOPPED"]
# Unit->host messages whose name has no _GET_ (a host that sends one is ignored and logged).
SENT_ONLY = {0x0080, 0x0081, 0x0444, 0x0464, 0x0466}
# The unit kinds of the per-message cell: letter, the models whose union it reports.
KINDS = [("M", ["TDC001", "KDC101", "TST001", "KST101", "BSC203", "BBD203"]), ("S", ["TSC001", "KSC101"]),
         ("T", ["TPZ001", "KPZ101"]), ("B", ["BPC301", "BPC303"]), ("G", ["TSG001", "KSG101"])]
KINDS_HEADER = "kinds (M S T B G)"
UPDATE_OF_MOTOR = {"DcServo": "MGMSG_MOT_GET_DCSTATUSUPDATE", "Brushless": "MGMSG_MOT_GET_DCSTATUSUPDATE",
                   "Stepper": "MGMSG_MOT_GET_STATUSUPDATE"}


def read(path):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except OSError as e:
        sys.stderr.write(f"apt_coverage.py: {e}\n")
        sys.exit(2)


def manual_tables(text):
    """{table name: set of IDs} from the "Messages Applicable to ..." sections."""
    tables = {}
    current = None
    for line in text.splitlines():
        m = re.match(r"#\s*\*\*Messages Applicable to (.+?)\*\*", line)
        if m:
            current = m.group(1).strip()
            tables[current] = set()
            continue
        if current and line.startswith("MGMSG"):
            for raw in re.findall(r"0x([0-9A-F]{3,4})(H?)", line):
                digits, h = raw
                # "0x002H", "0x005H", "0x006H" are 0x0002, 0x0005, 0x0006 (ERRATA).
                tables[current].add(int(digits, 16))
    return tables


def message_ids(text):
    """{MGMSG name: ID} from messages.def, one RIGSIM_APT_TABLE*(NAME, ID, ...) line per message."""
    return {m.group(1): int(m.group(2), 16)
            for m in re.finditer(r"^RIGSIM_APT_TABLE\w*\((MGMSG_\w+), 0x([0-9A-Fa-f]+),", text, re.M)}


def message_lists(text):
    """{takes list (kTsc, ...): [MGMSG names]} from messages.def's last column ("kTpz | kBpc"; 0: none)."""
    lists = {}
    for m in re.finditer(r"^RIGSIM_APT_TABLE\w*\((MGMSG_\w+), [^)]*, ([^,)]+)\)", text, re.M):
        for token in re.findall(r"k\w+", m.group(2)):
            lists.setdefault(token, []).append(m.group(1))
    return lists


def handlers(text):
    """MGMSG names of the on() overloads of a header (the `///` comment on or above the line)."""
    names = set()
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if re.search(r"\bvoid on\(const msg::\w+&", line):
            m = re.search(r"(MGMSG_\w+)", line) or (i > 0 and re.search(r"///.*?(MGMSG_\w+)", lines[i - 1]))
            if m:
                names.add(m.group(1))
    return names


def catalogue(text, lists):
    """{model: {kind, motor, takes (names), rack, rich}} from catalogue.cpp; `lists` (message_lists)
    gives the messages of the takes list a model names (`listed<kTsc>()`)."""
    functions = {}
    for m in re.finditer(r"constexpr ControllerModel (\w+)\(([^)]*)\)\s*\{(.*?)\n\}", text, re.S):
        functions[m.group(1)] = m.group(3)

    def body_facts(fn, seen=()):
        body = functions.get(fn, "")
        facts = {"takes": None, "kind": None, "motor": None, "rack": "c.rack = true" in body,
                 "rich": "rich_fault_reports = true" in body}
        t = re.search(r"listed<(k\w+)>\(\)", body)
        if t:
            facts["takes"] = lists[t.group(1)]
        k = re.search(r"UnitKind::(\w+)", body)
        if k:
            facts["kind"] = k.group(1)
        mk = re.search(r"MotorKind::(\w+)", body)
        if mk:
            facts["motor"] = mk.group(1)
        for called in re.findall(r"\b(\w+)\(name", body):
            if called in functions and called not in seen:
                inner = body_facts(called, seen + (fn,))
                for key, value in inner.items():
                    if facts[key] in (None, False):
                        facts[key] = value
        return facts

    models = {}
    listing = re.search(r"kControllers\{(.*?)\};", text, re.S).group(1)
    for m in re.finditer(r"(rich\()?(\w+)\((\"(\w+)\")?", listing):
        rich_wrap, fn, _, quoted = m.groups()
        if fn == "rich":
            continue
        facts = body_facts(fn)
        model = quoted or fn.upper()
        if model not in ORDER:
            continue
        facts["rich"] = facts["rich"] or bool(rich_wrap)
        facts["kind"] = facts["kind"] or "Motor"
        models[model] = facts
    return models


class Sources:
    """What rigsim's sources say: message IDs, models, handlers."""

    def __init__(self, root):
        apt = os.path.join(root, "emulator", "apt")
        self.apt = apt
        table = read(os.path.join(apt, "messages.def"))
        self.ids = message_ids(table)
        self.names = {v: k for k, v in self.ids.items()}
        self.models = catalogue(read(os.path.join(apt, "catalogue.cpp")), message_lists(table))
        self.generic = handlers(read(os.path.join(apt, "module.hpp"))) | handlers(read(os.path.join(apt, "apt_device.hpp")))
        self.rack = handlers(read(os.path.join(apt, "rack_modules.hpp")))
        for model in ORDER:
            if model not in self.models:
                raise SystemExit(f"apt_coverage.py: {model} is not in catalogue.cpp")

    def unit(self, model):
        """(acts, sends): the MGMSG names `model` acts on and those it sends."""
        facts = self.models[model]
        kind = facts["kind"] if facts["kind"] != "Motor" else (facts["motor"] or "DcServo")
        own = set()
        for h in KIND_HEADERS[kind]:
            own |= handlers(read(os.path.join(self.apt, h)))
        acts = set(self.generic) | (self.rack if facts["rack"] else set())
        if facts["takes"]:
            acts |= own & set(facts["takes"])
            sends = {n for n in facts["takes"] if "_GET_" in n}
        else:
            acts |= own
            sends = set(UNSOLICITED_MOTOR) | {UPDATE_OF_MOTOR[kind]}
            sends.add("MGMSG_HW_RICHRESPONSE" if facts["rich"] else "MGMSG_HW_RESPONSE")
        if kind != "Solenoid" and facts["takes"]:
            acts.discard("MGMSG_MOT_ACK_DCSTATUSUPDATE")   # their ack is PZ_ACK_PZSTATUSUPDATE
        if facts["rack"]:
            acts.discard("MGMSG_HUB_REQ_BAYUSED")           # a rack bay ignores it
        sends |= {n.replace("_REQ_", "_GET_") for n in acts if "_REQ_" in n}
        return acts, sends

    def unit_to_host(self, i):
        return "_GET_" in self.names[i] or i in SENT_ONLY


def coverage(src, manual_text):
    tables = manual_tables(manual_text)
    rows = []
    for model in ORDER:
        if model not in TABLE_OF:
            rows.append((model, None))
            continue
        table_name, page = TABLE_OF[model]
        table = tables[table_name]
        acts, sends = src.unit(model)
        done = {i for i in table if src.names.get(i) in acts | sends}
        missing = sorted(table - done)
        beyond = sorted(src.ids[n] for n in (src.models[model]["takes"] or []) if src.ids[n] not in table)
        rows.append((model, (table_name, page, len(table), len(done), missing, beyond, src.names)))
    return rows


def kind_cells(src):
    """{ID: "M I, S L, T I, B I, G –"}: what each unit kind does with every message of the table."""
    done = {}
    for letter, models in KINDS:
        sets = [src.unit(m) for m in models]
        done[letter] = set().union(*(a | s for a, s in sets))
    cells = {}
    for i, name in src.names.items():
        parts = []
        for letter, _ in KINDS:
            parts.append(f"{letter} {'I' if name in done[letter] else '–' if src.unit_to_host(i) else 'L'}")
        cells[i] = ", ".join(parts)
    return cells


def rows_with_kinds(doc, cells):
    """`doc` with the kinds cell (the 7th) of every message row set from `cells`; the rows'
    IDs not in the table, and the table's IDs without a row."""
    out, seen, unknown = [], set(), []
    for line in doc.split("\n"):
        if line.startswith("| ID | name | p. | direction | data | status |"):
            parts = line.split(" | ")
            if parts[6] != KINDS_HEADER:
                parts.insert(6, KINDS_HEADER)
            line = " | ".join(parts)
        elif re.match(r"\|---\|---\|---\|---\|---\|---\|---\|---\|(---\|)?$", line):
            line = "|---" * 9 + "|"
        else:
            m = re.match(r"\| 0x([0-9A-F]{4}) \|", line)
            if m and line.count(" | ") >= 7:
                i = int(m.group(1), 16)
                cells_of_line = line.split(" | ")
                if i not in cells:
                    unknown.append(m.group(1))
                else:
                    seen.add(i)
                    if len(cells_of_line) == 8:
                        cells_of_line.insert(6, cells[i])
                    else:
                        cells_of_line[6] = cells[i]
                    line = " | ".join(cells_of_line)
        out.append(line)
    return "\n".join(out), unknown, sorted(set(cells) - seen)


def short(name):
    return name.replace("MGMSG_", "")


def markdown(rows):
    out = [BEGIN,
           "| unit | cross-reference table | implemented / in the table | not implemented | taken beyond the table |",
           "|---|---|---|---|---|"]
    for model, data in rows:
        if data is None:
            out.append(f"| {model} | none in the manual | — | — | — |")
            continue
        table_name, page, total, done, missing, beyond, names = data
        miss = ", ".join(f"{short(names[i])} 0x{i:04X} ({'never sent' if '_GET_' in names[i] or i in SENT_ONLY else 'ignored and logged'})"
                         for i in missing) or "—"
        extra = ", ".join(short(names[i]) for i in beyond) or "—"
        out.append(f"| {model} | {table_name} (p.{page}) | **{done} / {total}** | {miss} | {extra} |")
    out.append(END)
    return "\n".join(out) + "\n"


def main(argv):
    manual = os.environ.get("RIGSIM_APT_MANUAL")
    check = write = None
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--manual" and args:
            manual = args.pop(0)
        elif a == "--check" and args:
            check = args.pop(0)
        elif a == "--write" and args:
            write = args.pop(0)
        elif a in ("-h", "--help"):
            print(__doc__)
            return 0
        elif not a.startswith("-"):
            root = a
        else:
            sys.stderr.write(f"apt_coverage.py: unknown argument {a}\n")
            return 2
    src = Sources(root)
    table = markdown(coverage(src, read(manual))) if manual else None
    if check is None and write is None:
        if table is None:
            sys.stderr.write("apt_coverage.py: the per-unit table needs the manual: --manual PATH or $RIGSIM_APT_MANUAL\n")
            return SKIP
        sys.stdout.write(table)
        return 0
    path = check or write
    doc = read(path)
    start, end = doc.find(BEGIN), doc.find(END)
    if start < 0 or end < 0:
        sys.stderr.write(f"apt_coverage.py: {path} has no {BEGIN} ... {END} block\n")
        return 1
    with_table = doc if table is None else doc[:start] + table[:-1] + doc[end + len(END):]
    expected, unknown, rowless = rows_with_kinds(with_table, kind_cells(src))
    if unknown or rowless:
        sys.stderr.write(f"apt_coverage.py: {path}: rows of IDs not in messages.def: {unknown}; "
                         f"messages without a row: {[f'0x{i:04X}' for i in rowless]}\n")
        return 1
    if write:
        with open(path, "w", encoding="utf-8") as f:
            f.write(expected)
        print(f"apt_coverage.py: wrote {path}")
        return 0
    if doc != expected:
        diff = [f"  -{a}\n  +{b}" for a, b in zip(doc.split("\n"), expected.split("\n")) if a != b]
        sys.stderr.write(f"apt_coverage.py: {path} is out of date (regenerate with scripts/apt_coverage.py --write "
                         f"{path}); {len(diff)} line(s) differ:\n" + "\n".join(diff[:20]) + "\n")
        return 1
    print(f"apt_coverage.py: {path} agrees with " + ("the sources (no manual: the per-unit table not checked)"
                                                      if table is None else "the manual and the sources"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
