#!/usr/bin/env python3
"""The coverage table of docs/protocol/mcs2.md, made from emulator/mcs2/properties.cpp.

Usage: scripts/mcs2_coverage.py [--check DOC | --write DOC] [SOURCE_DIR]

Reads every row of the MCS2 command and property table (path, scope, type, access, range, default,
non-volatile, the guide's section) and prints the Markdown table of docs/protocol/mcs2.md
("Commands and properties") with each row's status: how rigsim answers it (STATUS below, by path;
"implemented" otherwise). With --check DOC, exits 1 and prints the difference when DOC's table
between the markers is not what the sources give; --write DOC rewrites it. Standard library only.
"""
import difflib
import pathlib
import re
import sys

BEGIN = "<!-- mcs2_coverage.py: begin -->"
END = "<!-- mcs2_coverage.py: end -->"

NO_IOM = "with the I/O module (rig key `io_module`): stored and read back; without it 257 NO_IOM_PRESENT, as such a unit answers"
# How rigsim answers the rows that are not simply read and written by the table or acted on.
STATUS = {
    "*CLS": "implemented: empties the connection's error queue",
    "*ESE": "implemented: stored per connection, no effect (Table 6.1)",
    "*ESR": "implemented: 0 (\"no effect\")",
    "*IDN": "implemented: `SmarAct GmbH,MCS2,<serial>,<firmware>` (format not given by the guide)",
    "*OPC": "implemented: no effect; the query answers 1",
    "*RST": "implemented: power-up state, then the connection is closed (\"reconnect necessary\")",
    "*SRE": "implemented: stored per connection, no effect",
    "*STB": "implemented: 4 while the connection's error queue holds errors, else 0",
    "*TST": "implemented: 0",
    "*WAI": "implemented: no effect",
    ":CGRoup:OPEN": "implemented: direct (0); external (1): armed by CLOSe, run at the trigger input's edge (input mode 3, else 265; without the I/O module 257)",
    ":STReam:OPEN": "implemented: direct (0); external (1, 2): started at the trigger input's edge once ready (input mode 2, else 265; without the I/O module 257); 2's sync clock is taken to be in step with the base rate",
    "[:PROPerty]:DEVice:HMODule:LOPTions[:CURRent]": "answered as a unit without a hand control module: 256 NO_HM_PRESENT",
    "[:PROPerty]:DEVice:HMODule:LOPTions:DEFault": "answered as a unit without a hand control module: 256 NO_HM_PRESENT",
    "[:PROPerty]:DEVice:TRIGger:INPut:MODE": "with the I/O module: the control API's `trig_in` drives the input; 1 emergency stop, 2 stream, 3 command group, 4 event (the library's, nothing on the ASCII wire); without it 257 (4.13.1)",
    "[:PROPerty]:DEVice:TRIGger:INPut:CONDition": "with the I/O module: the edge that acts; without it 257",
    "[:PROPerty]:DEVice:ESTop:MODE": "implemented: 0 stops, 1 also locks until written, 2 also until the input's inverse edge (2.17.2)",
    "[:PROPerty]:MODule#:IOModule:OPTions": NO_IOM,
    "[:PROPerty]:MODule#:IOModule:VOLTage": NO_IOM,
    "[:PROPerty]:MODule#:IOModule:AINPut:RANGe": NO_IOM,
    "[:PROPerty]:MODule#:AUXiliary:DINPut[:VALue]": "with the I/O module: 0 (nothing wired to GP-DIN); without it 257",
    "[:PROPerty]:MODule#:AUXiliary:DOUTput[:VALue]": NO_IOM,
    "[:PROPerty]:MODule#:AUXiliary:DOUTput:SET": "with the I/O module: sets the given bits of the outputs' value; without it 257",
    "[:PROPerty]:MODule#:AUXiliary:DOUTput:CLEar": "with the I/O module: clears the given bits; without it 257",
    "[:PROPerty]:MODule#:AUXiliary:AOUTput:VALue#": NO_IOM,
    "[:PROPerty]:CHANnel#:CLINput:AUXiliary[:VALue]": "0 (nothing wired to the aux input); 257 when Aux Input Select names the absent I/O module",
    "[:PROPerty]:CHANnel#:AUXiliary:IOModule:INPut:VALue#": "with the I/O module: 0 (nothing wired to AIN); without it 257",
    "[:PROPerty]:CHANnel#:TRIGger:OUTPut:MODE": "with the I/O module: stored (no output line to watch), 41 for position compare with LMAX < LMIN; without it 257 (4.14.1)",
    "[:PROPerty]:CHANnel#:CLINput[:SELect]": "implemented: 0 and 1; 2 (AUX_IN): the aux feedback is not modelled: 32765 FEATURE_NOT_SUPPORTED with the I/O module, 257 without",
    "[:PROPerty]:CHANnel#:ACTuator:MODE": "implemented: 0, 1; 2 (low vibration) needs a feature permission: 35",
    "[:PROPerty]:CHANnel#:SCORrection:OPTions": "implemented: bits 0 and 2 read 1; bit 4 (ASC) needs a feature permission: 35",
    "[:PROPerty]:CHANnel#:CALibration:OPTions": "implemented: bit 1 on a coded-mark type sets Distance Code Inverted to what it finds (0); bit 2 (ASC) needs a feature permission: 35; bits 0 and 8 are taken (the calibration run is not modelled as a path)",
    "[:PROPerty]:CHANnel#:REFerencing:DCINverted": "stored; a calibration with option bit 1 sets it to 0 (rigsim's coded marks run as the type says)",
    "[:PROPerty]:CHANnel#:TUNing:WPRotection": "implemented: reads 1 while protected, 0 once 0x534D4152 (1397571922) is written",
    "[:PROPerty]:CHANnel#:TUNing:HTYPe": "stored (PicoScale heads are not modelled)",
    "[:PROPerty]:CHANnel#:TUNing:MTYPe": "stored (informational, 4.8.1: the configured type's motion decides)",
    "[:PROPerty]:CHANnel#:TUNing:RTYPe": "stored (the configured type's reference decides how it is referenced)",
    "[:PROPerty]:CHANnel#:TUNing:BASE:UNIT": "stored (informational, 4.8.3)",
    "[:PROPerty]:CHANnel#:TUNing:BASE:RESolution": "stored (informational, 4.8.4)",
    "[:PROPerty]:CHANnel#:MCLFrequency:DEFault": "implemented: the Max Closed Loop Frequency's value at power-up",
    "[:PROPerty]:CHANnel#:TUNing:GAIN:P": "stored (the PID loop is not modelled: moves follow exact profiles)",
    "[:PROPerty]:CHANnel#:TUNing:GAIN:I": "stored (the PID loop is not modelled)",
    "[:PROPerty]:CHANnel#:TUNing:GAIN:D": "stored (the PID loop is not modelled)",
    "[:PROPerty]:CHANnel#:TUNing:GAIN:SHIFt": "stored (the PID loop is not modelled)",
    "[:PROPerty]:CHANnel#:TUNing:AWINdup": "stored (the PID loop is not modelled)",
    "[:PROPerty]:CHANnel#:TUNing:ESDetection:DISTance": "stored (an end stop is detected where the stage meets it)",
    "[:PROPerty]:CHANnel#:TUNing:ESDetection:COUNter": "stored",
    "[:PROPerty]:CHANnel#:TUNing:THReshold:TREached": "stored (targets are reached exactly)",
    "[:PROPerty]:CHANnel#:TUNing:THReshold:THOLd": "stored",
    "[:PROPerty]:CHANnel#:POSition:MSHift": "stored (positions are exact: no averaging to do)",
    "[:PROPerty]:CHANnel#:FELimit": "stored (an exact profile has no following error; a stall ends a move as an end stop)",
    "[:PROPerty]:CHANnel#:TTZVoltage:THReshold[:HOLD]": "stored (the piezo voltage while holding is not modelled)",
    "[:PROPerty]:CHANnel#:TRIGger:OUTPut:POLarity": "stored (no output without an I/O module)",
    "[:PROPerty]:CHANnel#:TRIGger:OUTPut:PWIDth": "stored (no output without an I/O module)",
    "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:THReshold[:STARt]": "stored (no output without an I/O module)",
    "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:INCRement": "stored (no output without an I/O module)",
    "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:DIRection": "stored (no output without an I/O module)",
    "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:LMIN": "stored (no output without an I/O module)",
    "[:PROPerty]:CHANnel#:TRIGger:PCOMpare:LMAX": "stored (no output without an I/O module)",
    "[:PROPerty]:CHANnel#:AUXiliary:PTYPe": "stored (the aux input is not modelled)",
    "[:PROPerty]:CHANnel#:AUXiliary:ISELect": "stored",
    "[:PROPerty]:CHANnel#:AUXiliary:IOModule:INPut:INDex": "stored",
    "[:PROPerty]:CHANnel#:AUXiliary:DINVersion": "stored",
    "[:PROPerty]:DEVice:NETWork:DISCover:MODE": "stored (no discovery protocol on the loopback)",
    "[:PROPerty]:DEVice:STReaming:SYNCrate": "stored (external sync needs the I/O module)",
    "[:PROPerty]:CHANnel#:CLINput:SENSor:SELect": "implemented: 1 (CALC_SYS) only on a PicoScale type, else 19",
    "[:PROPerty]:CHANnel#:SENSor:MODE": "firmware `current` only: Sensor Power Mode as EPICS motorSmarAct and BLISS send it",
    "[:PROPerty]:CHANnel#:SENSor:DELay": "firmware `current` only: Sensor Power Save Delay as EPICS motorSmarAct sends it",
    "[:PROPerty]:MODule:STATe": "firmware `current` only: module 0's state (BLISS sends it without an index)",
    "[:PROPerty]:CHANnel#:FERRor": "firmware `current` only: target minus position while moving, else 0 (EPICS motorSmarAct's report)",
}


def rows(src):
    text = (src / "emulator/mcs2/properties.cpp").read_text()
    pattern = re.compile(r'Property\{Id::(\w+), "([^"]+)", Scope::(\w+), Type::(\w+), Access::(\w+), Kind::(\w+), '
                         r'([^,]+), ([^,]+), ([^,]+), (true|false), (true|false), "([^"]*)"\}')
    out = [m.groups() for m in pattern.finditer(text)]
    if len(out) < 120:
        sys.exit("mcs2_coverage.py: the table was not found in emulator/mcs2/properties.cpp")
    return out


def number(expr):
    expr = expr.strip().replace("'", "")
    names = {"kPos": "100e12", "kI32Max": "2147483647", "kInfinite": "4294967295", "-kPos": "-100e12"}
    return names.get(expr, expr)


def table(src):
    lines = ["| command or property | guide | type | access | range | default | status |",
             "|---|---|---|---|---|---|---|"]
    for _id, path, scope, typ, access, kind, lo, hi, initial, nv, cg, section in rows(src):
        access_text = {"R": "R", "W": "W", "RW": "RW", "Tuning": "R(W)"}[access] + (", NV" if nv == "true" else "")
        numeric = typ in ("I32", "I64")
        stored = kind == "Stored" or path in STATUS and STATUS[path].startswith("stored")
        rng = "%s … %s" % (number(lo), number(hi)) if numeric and (lo.strip() != "0" or hi.strip() != "0") else ""
        default = number(initial) if numeric and access in ("RW", "Tuning") and not path.endswith("#") else ""
        status = STATUS.get(path, "implemented")
        lines.append("| `%s` | %s | %s | %s | %s | %s | %s |" % (path, section, typ if typ != "None" else "-", access_text,
                                                              rng, default, status))
    return "\n".join(lines)


def main(argv):
    mode, doc, src = None, None, pathlib.Path(__file__).resolve().parent.parent
    args = list(argv)
    while args:
        a = args.pop(0)
        if a in ("--check", "--write") and args:
            mode, doc = a, pathlib.Path(args.pop(0))
        elif not a.startswith("-"):
            src = pathlib.Path(a)
        else:
            print(__doc__, file=sys.stderr)
            return 2
    generated = table(src)
    if not mode:
        print(generated)
        return 0
    text = doc.read_text()
    if BEGIN not in text or END not in text:
        print("%s: no %s ... %s markers" % (doc, BEGIN, END), file=sys.stderr)
        return 2
    head, rest = text.split(BEGIN, 1)
    current, tail = rest.split(END, 1)
    wanted = head + BEGIN + "\n" + generated + "\n" + END + tail
    if mode == "--write":
        doc.write_text(wanted)
        return 0
    if text != wanted:
        sys.stdout.writelines(difflib.unified_diff(text.splitlines(True), wanted.splitlines(True), str(doc), "generated"))
        print("run scripts/mcs2_coverage.py --write %s" % doc, file=sys.stderr)
        return 1
    print("%s: the coverage table matches the %d rows of emulator/mcs2/properties.cpp" % (doc, len(rows(src))))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
