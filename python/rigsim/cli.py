"""rigsimctl: every route of rigsimd's control API as a sub-command (docs/cli.md#rigsimctl)."""

from __future__ import annotations

import argparse
import json
import os
import sys
import urllib.error
from typing import Any, Callable, Final, Iterable, Mapping, Sequence, TextIO

from rigsim.control import DEFAULT_CONTROL, ControlClient, ControlError, JsonObject, NotControlApi
from rigsim.control import control_url as normalize_url

EPILOG: Final[str] = f"""The control API is found by --control ADDRESS (HOST:PORT as rigsimd --control takes it,
or http://HOST:PORT), else --endpoints FILE (its "control" key, as rigsimd --endpoints-json
writes it), else $RIGSIM_CONTROL, else {DEFAULT_CONTROL} (where the built-in default rig
serves it). A daemon started with --control-token takes --token TOKEN, --token-file FILE or
$RIGSIM_CONTROL_TOKEN. Answers print as indented JSON (--format table: a short table).
Errors go to standard error in one line, exit status 1."""


# A sub-command: its answer printed to `out`.
Command = Callable[[ControlClient, argparse.Namespace, TextIO], None]


class UsageError(Exception):
    """A command line the API cannot be asked with (bad key=value, no control URL)."""


def parse_value(text: str) -> Any:
    """key=value values: JSON when they parse (1.5, true, null, "x"), else the text itself."""
    try:
        return json.loads(text)
    except ValueError:
        return text


def parse_fields(pairs: Iterable[str]) -> dict[str, Any]:
    fields: dict[str, Any] = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key:
            raise UsageError(f"expected key=value, got {pair!r}")
        fields[key] = parse_value(value)
    return fields


def control_url(args: argparse.Namespace) -> str:
    """The control API's URL: --control, else --endpoints' "control" key, else $RIGSIM_CONTROL,
    else the default rig's (each a URL or HOST:PORT)."""
    return normalize_url(_control_address(args))


def _control_address(args: argparse.Namespace) -> str:
    if getattr(args, "control", None):
        return str(args.control)
    if getattr(args, "endpoints", None):
        try:
            with open(args.endpoints, encoding="utf-8") as f:
                doc = json.load(f)
        except (OSError, ValueError) as e:
            raise UsageError(f"cannot read the endpoints file {args.endpoints}: {e}") from None
        control = doc.get("control") if isinstance(doc, dict) else None
        if not isinstance(control, str):
            raise UsageError(f"{args.endpoints} names no control API (was rigsimd started with --control?)")
        return control
    if os.environ.get("RIGSIM_CONTROL"):
        return os.environ["RIGSIM_CONTROL"]
    return DEFAULT_CONTROL


def control_token(args: argparse.Namespace) -> str | None:
    """--token, else --token-file's first line, else None (the client reads RIGSIM_CONTROL_TOKEN)."""
    if getattr(args, "token", None):
        return str(args.token)
    if getattr(args, "token_file", None):
        try:
            with open(args.token_file, encoding="utf-8") as f:
                token = f.readline().strip()
        except OSError as e:
            raise UsageError(f"cannot read the token file {args.token_file}: {e.strerror}") from None
        if not token:
            raise UsageError(f"the token file {args.token_file} is empty")
        return token
    return None


# ---- output ----

def table(rows: Iterable[Mapping[str, Any]], columns: Sequence[tuple[str, str]]) -> str:
    """A short left-aligned text table of `rows` (dicts) with `columns` (key, heading)."""
    cells = [[heading for _, heading in columns]]
    for row in rows:
        cells.append([_cell(row.get(key)) for key, _ in columns])
    widths = [max(len(r[i]) for r in cells) for i in range(len(columns))]
    return "\n".join("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in cells)


def _cell(value: object) -> str:
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, dict):
        if "name" in value:
            return str(value["name"])
        if "hex" in value:
            return str(value["hex"])
        return json.dumps(value, separators=(",", ":"))
    if isinstance(value, list):
        return ",".join(str(v) for v in value)
    return str(value)


def _clock_table(clock: Mapping[str, Any]) -> str:
    return table([clock], [("now_ms", "now_ms"), ("paused", "paused"), ("time_scale", "scale"),
                           ("tick_hz", "tick_hz"), ("reached_ms", "reached_ms")])


def _log_rows(answer: JsonObject) -> list[dict[str, Any]]:
    rows = []
    for e in answer.get("entries", []):
        decoded = e.get("decoded") or {}
        what = decoded.get("text") or decoded.get("name") or decoded.get("id") or e.get("hex")
        rows.append({"seq": e.get("seq"), "time_ms": e.get("time_ms"), "dir": e.get("direction"),
                     "what": what, "notes": "; ".join(e.get("notes", []))})
    return rows


def _numbers(values: Iterable[float], digits: int) -> list[str]:
    return [f"{v:.{digits}f}" for v in values]


def _joint_cell(frame: JsonObject) -> str:
    if frame.get("tool"):
        return "tool"
    joint = frame.get("joint")
    if not joint:
        return "fixed"
    return f"{joint['type']} {joint['device']}/{joint['channel']} = {joint['position']:.4f}"


def _frames_table(answer: JsonObject) -> str:
    """One row per frame and tool point: its joint and its world placement; then the contacts."""
    rows = []
    for frame in answer.get("frames", []) + answer.get("tools", []):
        world = frame["world"]
        x, y, z = _numbers(world["position_mm"], 4)
        roll, pitch, yaw = _numbers(world["rpy_deg"], 4)
        rows.append({"name": frame["name"], "parent": frame.get("parent"), "joint": _joint_cell(frame),
                     "x": x, "y": y, "z": z, "roll": roll, "pitch": pitch, "yaw": yaw})
    out = table(rows, [("name", "name"), ("parent", "parent"), ("joint", "joint"), ("x", "x_mm"),
                       ("y", "y_mm"), ("z", "z_mm"), ("roll", "roll_deg"), ("pitch", "pitch_deg"),
                       ("yaw", "yaw_deg")])
    contacts = [" - ".join(c["frames"]) for c in answer.get("collisions", [])]
    return out + "\n\ncollisions: " + (", ".join(contacts) if contacts else "none")


def _frame_table(frame: JsonObject) -> str:
    """One frame: its world and parent-relative placements, position, quaternion and angles."""
    rows = []
    for ref, key in (("world", "world"), ("parent", "parent_relative")):
        placement = frame[key]
        row = {"ref": ref}
        row.update(zip(("x", "y", "z"), _numbers(placement["position_mm"], 4)))
        row.update(zip(("qw", "qx", "qy", "qz"), _numbers(placement["quaternion"], 6)))
        row.update(zip(("roll", "pitch", "yaw"), _numbers(placement["rpy_deg"], 4)))
        rows.append(row)
    head = f"{frame['name']} (parent {frame.get('parent') or '-'}, {_joint_cell(frame)})"
    return head + "\n" + table(rows, [("ref", "relative to"), ("x", "x_mm"), ("y", "y_mm"), ("z", "z_mm"),
                                      ("qw", "qw"), ("qx", "qx"), ("qy", "qy"), ("qz", "qz"),
                                      ("roll", "roll_deg"), ("pitch", "pitch_deg"), ("yaw", "yaw_deg")])


def render_table(kind: str, answer: Any) -> str | None:
    """A short table for the answers that have one, else None (JSON is printed)."""
    if kind == "rig":
        devices = answer.get("devices", [])
        columns = [("name", "name"), ("protocol", "protocol"), ("model", "model"), ("firmware", "firmware"),
                   ("tcp", "tcp"), ("pty", "pty")]
        if any(d.get("rfc2217") for d in devices):   # rigsimd --rfc2217, a device's rfc2217_port
            columns.append(("rfc2217", "rfc2217"))
        out = table(devices, columns)
        return out + "\n\n" + _clock_table(answer.get("clock", {}))
    if kind == "clock":
        return _clock_table(answer)
    if kind == "state":
        # An MCS2 channel has its 32-bit "state" (word and activity) where the others have "status".
        channels = [dict(c, status=c["state"]["activity"]) if "status" not in c and isinstance(c.get("state"), dict)
                    else c for c in answer.get("channels", [])]
        return table(channels, [
            ("index", "ch"), ("kind", "kind"), ("position_si", "position_si"),
            ("position_protocol", "protocol"), ("moving", "moving"),
            ("referenced", "referenced"), ("status", "status")])
    if kind == "faults":
        return table(answer, [("id", "id"), ("device", "device"), ("channel", "ch"),
                              ("kind", "kind"), ("active", "active"), ("since_ms", "since_ms"),
                              ("params", "params")])
    if kind == "frames":
        return _frames_table(answer)
    if kind == "frame":
        return _frame_table(answer)
    if kind == "log":
        return table(_log_rows(answer), [("seq", "seq"), ("time_ms", "time_ms"), ("dir", "dir"),
                                         ("what", "what"), ("notes", "notes")])
    return None


def emit(args: argparse.Namespace, kind: str, answer: Any, out: TextIO) -> None:
    text = render_table(kind, answer) if args.format == "table" else None
    if text is None:
        text = json.dumps(answer, indent=2, sort_keys=False)
    out.write(text + "\n")


# ---- sub-commands ----

def cmd_rig(client: ControlClient, args: argparse.Namespace, out: TextIO) -> None:
    emit(args, "rig", client.rig(), out)


def cmd_state(client: ControlClient, args: argparse.Namespace, out: TextIO) -> None:
    emit(args, "state", client.state(args.name), out)


def cmd_set(client: ControlClient, args: argparse.Namespace, out: TextIO) -> None:
    fields = parse_fields(args.fields)
    if not fields:
        raise UsageError("set: give at least one key=value (position_si, referenced, limit_switch, sensor)")
    emit(args, "channel", client.set(args.name, args.channel, **fields), out)


def cmd_clock(client: ControlClient, args: argparse.Namespace, out: TextIO) -> None:
    action = args.action or "show"
    if action == "show":
        answer = client.clock()
    elif action == "pause":
        answer = client.pause()
    elif action == "resume":
        answer = client.resume()
    elif action == "step":
        answer = client.step(args.ms)
    elif action == "scale":
        answer = client.scale(args.factor)
    else:
        answer = client.run_until_idle(args.max_ms, check=False)   # the answer says "idle"
    emit(args, "clock", answer, out)


def cmd_fault(client: ControlClient, args: argparse.Namespace, out: TextIO) -> None:
    action = args.action
    if action == "add":
        params = parse_fields(args.params)
        emit(args, "fault", client.add_fault(args.device, args.kind, args.channel, **params), out)
    elif action == "list":
        emit(args, "faults", client.faults(), out)
    elif action == "rm":
        emit(args, "removed", client.clear_fault(args.id), out)
    else:
        emit(args, "removed", client.clear_faults(), out)


def cmd_frames(client: ControlClient, args: argparse.Namespace, out: TextIO) -> None:
    if args.name is None:
        emit(args, "frames", client.frames(), out)
    else:
        emit(args, "frame", client.frame(args.name), out)


def cmd_events(client: ControlClient, args: argparse.Namespace, out: TextIO) -> None:
    def names(option: list[str] | None) -> list[str] | None:
        return [n for d in option for n in d.split(",") if n] if option else None
    count = 0
    stream = client.events(names(args.device), timeout=args.timeout, type=names(args.type))
    try:
        for event in stream:
            out.write(json.dumps(event, separators=(",", ":")) + "\n")
            out.flush()
            count += 1
            if args.count is not None and count >= args.count:
                break
    except KeyboardInterrupt:
        pass
    finally:
        stream.close()


def cmd_reset(client: ControlClient, args: argparse.Namespace, out: TextIO) -> None:
    emit(args, "reset", client.reset(keep_saved=not args.erase_saved), out)


def cmd_log(client: ControlClient, args: argparse.Namespace, out: TextIO) -> None:
    if args.clear:
        emit(args, "cleared", client.clear_log(args.name), out)
    else:
        emit(args, "log", client.log(args.name, args.last), out)


# ---- the parser ----

def _common(suppress: bool) -> argparse.ArgumentParser:
    """The options every sub-command takes too (before or after the sub-command's name)."""
    p = argparse.ArgumentParser(add_help=False)
    default = argparse.SUPPRESS if suppress else None
    p.add_argument("--control", metavar="ADDRESS", default=default,
                   help=f"the control API: HOST:PORT as rigsimd --control takes it, or "
                        f"http://HOST:PORT (default: $RIGSIM_CONTROL, else {DEFAULT_CONTROL}, the default rig's)")
    p.add_argument("--endpoints", metavar="FILE", default=default,
                   help='the endpoints JSON rigsimd wrote (--endpoints-json); its "control" key')
    p.add_argument("--token", metavar="TOKEN", default=default,
                   help="the daemon's --control-token (default: $RIGSIM_CONTROL_TOKEN)")
    p.add_argument("--token-file", metavar="FILE", default=default,
                   help="read the token from FILE's first line (rigsimd --control-token-file)")
    p.add_argument("--format", choices=("json", "table"),
                   default=argparse.SUPPRESS if suppress else "json",
                   help="indented JSON (default) or a short table")
    return p


def _sub(subs: argparse._SubParsersAction[argparse.ArgumentParser], name: str, func: Command, help_text: str,
         common: argparse.ArgumentParser) -> argparse.ArgumentParser:
    p = subs.add_parser(name, help=help_text, description=help_text, parents=[common])
    p.set_defaults(func=func)
    return p


def build_parser() -> argparse.ArgumentParser:
    common = _common(suppress=True)
    parser = argparse.ArgumentParser(
        prog="rigsimctl", parents=[_common(suppress=False)],
        description="Drive a running rigsimd through its control API: the rig, the clock, "
                    "device state, frames, faults, events, reset and wire logs.",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    subs = parser.add_subparsers(dest="command", metavar="COMMAND")
    subs.required = True

    _sub(subs, "rig", cmd_rig, "GET /api/rig: the devices, their endpoints and the clock", common)

    p = _sub(subs, "state", cmd_state, "GET /api/devices/NAME: a device's state, channel by channel", common)
    p.add_argument("name", metavar="NAME")

    p = _sub(subs, "set", cmd_set, "PATCH /api/devices/NAME/channels/CH: set a channel's state "
             "(position_si=M, referenced=true|false, limit_switch=forward|reverse|none, "
             "sensor=enabled|disabled|power_save)", common)
    p.add_argument("name", metavar="NAME")
    p.add_argument("channel", metavar="CH", type=int)
    p.add_argument("fields", metavar="key=value", nargs="*",
                   help="values are read as JSON when they parse (1e-3, true), else as text")

    p = _sub(subs, "clock", cmd_clock, "GET or POST /api/clock: show, pause, resume, step, "
             "scale or run the clock until idle", common)
    actions = p.add_subparsers(dest="action", metavar="ACTION")
    for name, text in (("show", "GET /api/clock (the default)"),
                       ("pause", "stop the clock at the current tick"),
                       ("resume", "run the clock again from the current tick")):
        actions.add_parser(name, help=text, description=text, parents=[common])
    a = actions.add_parser("step", help="advance the clock MS ms now", description="advance the clock MS ms now",
                           parents=[common])
    a.add_argument("ms", metavar="MS", type=int)
    a = actions.add_parser("scale", help="clock seconds per wall second from now on",
                           description="clock seconds per wall second from now on", parents=[common])
    a.add_argument("factor", metavar="X", type=float)
    a = actions.add_parser("run-until-idle", parents=[common],
                           help="advance as fast as possible until nothing moves",
                           description="advance as fast as possible until nothing moves, at most "
                                       "--max-ms of clock time")
    a.add_argument("--max-ms", type=int, default=600_000, help="clock time limit (default 600000)")

    p = _sub(subs, "fault", cmd_fault, "/api/faults: add, list, remove or clear faults", common)
    actions = p.add_subparsers(dest="action", metavar="ACTION")
    actions.required = True
    a = actions.add_parser("add", parents=[common], help="POST /api/faults: inject a fault",
                           description="POST /api/faults: inject a fault KIND (stall, slip, "
                           "sensor_failure, reference_lost, limit_switch, unplugged, drop_bytes, "
                           "corrupt_bytes, latency, slicer, bandwidth, reset, slow_close, hang_close, "
                           "cut_after, garbage_close, overrun, baud_mismatch, power_cycle) on DEVICE")
    a.add_argument("device", metavar="DEVICE")
    a.add_argument("kind", metavar="KIND")
    a.add_argument("--channel", type=int, default=None, help="the channel (default 0)")
    a.add_argument("params", metavar="key=value", nargs="*",
                   help="the kind's parameters (probability=0.5 direction=in seed=1 latency_ms=20 "
                        "bytes_per_s=960 after_ms=0 ...)")
    actions.add_parser("list", parents=[common], help="GET /api/faults", description="GET /api/faults")
    a = actions.add_parser("rm", parents=[common], help="DELETE /api/faults/ID", description="DELETE /api/faults/ID")
    a.add_argument("id", metavar="ID", type=int)
    actions.add_parser("clear", parents=[common], help="DELETE /api/faults: remove every fault",
                       description="DELETE /api/faults: remove every fault")

    p = _sub(subs, "frames", cmd_frames, "GET /api/frames[/NAME]: every frame and tool point of "
             "the rig's kinematics (world and parent-relative placement), or one", common)
    p.add_argument("name", metavar="NAME", nargs="?", default=None, help="only this frame or tool point")

    p = _sub(subs, "events", cmd_events, "GET /api/events: print each event as a JSON line "
             "until Ctrl-C", common)
    p.add_argument("--device", action="append", metavar="NAME",
                   help="only this device's events (repeat, or a,b)")
    p.add_argument("--type", action="append", metavar="TYPE",
                   help="only events of this type (repeat, or a,b: frames,move_ended)")
    p.add_argument("--count", type=int, default=None, help="stop after N events")
    p.add_argument("--timeout", type=float, default=None,
                   help="stop when no event came for S seconds")

    p = _sub(subs, "reset", cmd_reset, "POST /api/reset: every device back to power-up, faults "
             "removed, wire logs cleared", common)
    p.add_argument("--erase-saved", action="store_true",
                   help="forget the saved settings too ({\"keep_saved\": false})")

    p = _sub(subs, "log", cmd_log, "GET /api/devices/NAME/log: the device's wire log", common)
    p.add_argument("name", metavar="NAME")
    p.add_argument("--last", type=int, default=None, metavar="N", help="only the last N entries")
    p.add_argument("--clear", action="store_true", help="DELETE the log instead")
    return parser


def _default_hint(url: str | None) -> str:
    if url != normalize_url(DEFAULT_CONTROL):
        return ""
    return (f" ({DEFAULT_CONTROL} is the default rig's; for another daemon pass --control HOST:PORT, "
            "--endpoints FILE or set RIGSIM_CONTROL)")


def main(argv: Sequence[str] | None = None, out: TextIO | None = None) -> int:
    out = out or sys.stdout
    parser = build_parser()
    args, extra = parser.parse_known_args(argv)
    # argparse stops filling a nargs="*" positional at the first option: key=value pairs after
    # one (fault add D K --channel 1 a=b) come back unknown; they belong to that positional.
    pairs_attr = {"set": "fields", "fault": "params"}.get(args.command)
    if pairs_attr and hasattr(args, pairs_attr) and all("=" in x and not x.startswith("-") for x in extra):
        getattr(args, pairs_attr).extend(extra)
    elif extra:
        parser.error("unrecognized arguments: " + " ".join(extra))
    url = None
    try:
        url = control_url(args)
        args.func(ControlClient(url, token=control_token(args)), args, out)
    except ControlError as e:
        print(f"rigsimctl: {e.status}: {e.message}", file=sys.stderr)
        return 1
    except UsageError as e:
        print(f"rigsimctl: {e}", file=sys.stderr)
        return 1
    except NotControlApi as e:
        print(f"rigsimctl: {e}", file=sys.stderr)
        return 1
    except urllib.error.URLError as e:
        print(f"rigsimctl: cannot reach the control API at {url}: {e.reason}"
              f"{_default_hint(url)}", file=sys.stderr)
        return 1
    except (OSError, ValueError) as e:
        print(f"rigsimctl: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
