"""A tiny stand-in for rigsimd's control API (http.server), answering per the contract
(docs/control-api.md) for the routes the real daemon may not serve yet.

It holds two devices, "mcs0" (MCS, 3 channels) and "apt0" (APT, 1 channel), records every
request in `requests` ((method, path, body) tuples) and its headers in `headers` and serves /api/events from `publish()`:
as rigsimd does, a stream gets only what is published once it is open (`wait_for_subscribers()`)."""

import json
import threading
import urllib.parse
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer


def _channel(index, kind="linear"):
    return {"index": index, "kind": kind, "position_si": 0.0, "si_unit": "m",
            "position_protocol": 0, "protocol_unit": "nm", "velocity_si": 0.0, "moving": False,
            "referenced": False, "status": {"code": 0, "name": "stopped"}, "limits": {}}


def _placement(position_mm, quaternion, rpy_deg):
    return {"position_mm": position_mm, "quaternion": quaternion, "rpy_deg": rpy_deg}


_IDENTITY = _placement([0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
_YAW_90 = [0.7071067811865476, 0.0, 0.0, 0.7071067811865476]


def _frames():
    """A table, a rotation stage turned 90 degrees (apt0/0) 50 mm up, an x stage on it (mcs0/0)
    at 2 mm, and a sample 40 mm above the x carriage."""
    return {
        "frames": [
            {"name": "table", "parent": None, "tool": False, "joint": None,
             "world": _IDENTITY, "parent_relative": _IDENTITY},
            {"name": "rot", "parent": "table", "tool": False,
             "joint": {"type": "revolute", "device": "apt0", "channel": 0, "position": 90.0},
             "world": _placement([0.0, 0.0, 50.0], _YAW_90, [0.0, 0.0, 90.0]),
             "parent_relative": _placement([0.0, 0.0, 50.0], _YAW_90, [0.0, 0.0, 90.0])},
            {"name": "x", "parent": "rot", "tool": False,
             "joint": {"type": "prismatic", "device": "mcs0", "channel": 0, "position": 2.0},
             "world": _placement([0.0, 2.0, 50.0], _YAW_90, [0.0, 0.0, 90.0]),
             "parent_relative": _placement([2.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0])},
        ],
        "tools": [
            {"name": "sample", "parent": "x", "tool": True, "joint": None,
             "world": _placement([0.0, 2.0, 90.0], _YAW_90, [0.0, 0.0, 90.0]),
             "parent_relative": _placement([0.0, 0.0, 40.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0])},
        ],
        "collisions": [{"frames": ["x", "rot"]}],
    }


class FakeControl:
    """Start with `with FakeControl() as fake:`; `fake.url` is the API's URL."""

    ONE_OFF = ("reference_lost", "power_cycle")

    def __init__(self):
        self.requests = []
        self.headers = []         # each request's headers (an email.message.Message), in order
        self.lock = threading.Condition()
        self.events = []          # every published event, in order
        self.subscribers = 0      # event streams open now
        self.closing = False
        self.clock = {"now_ticks": 0, "now_ms": 0.0, "tick_hz": 1000, "time_scale": 1.0, "paused": False}
        self.devices = {
            "mcs0": {"name": "mcs0", "protocol": "mcs", "model": "MCS-3D", "firmware": "1.2.44",
                     "endpoints": {"tcp": "127.0.0.1:1", "pty": "/dev/pts/1"},
                     "channels": [_channel(i) for i in range(3)], "faults": [],
                     "link": {"unplugged": False}},
            "apt0": {"name": "apt0", "protocol": "apt", "model": "TDC001", "firmware": "issue-3",
                     "endpoints": {"tcp": "127.0.0.1:2", "pty": "/dev/pts/2"},
                     "channels": [_channel(0)], "faults": [], "link": {"unplugged": False}},
        }
        self.logs = {name: [{"seq": 1, "time_ms": 5.0, "direction": "in", "peer": "tcp",
                             "hex": "3a4750300a", "decoded": {"text": ":GP0", "command": "GP"},
                             "notes": ["sent while not referenced"]},
                            {"seq": 2, "time_ms": 5.0, "direction": "out", "peer": "tcp",
                             "hex": "3a50302c300a", "unprompted": False,
                             "decoded": {"text": ":P0,0"}, "notes": []}]
                     for name in self.devices}
        self.busy_ms = None       # run_until_idle: None, 10 ms then idle; else the clock time still busy
        self.acks_on_poll = None  # a device whose full log read finds one more inbound ack (a driver's thread)
        self.faults = {}
        self.next_fault_id = 1
        self.frames = _frames()
        self.server = ThreadingHTTPServer(("127.0.0.1", 0), _handler(self))
        self.server.daemon_threads = True
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}"
        self.thread = threading.Thread(target=self.server.serve_forever, args=(0.05,), daemon=True)

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        with self.lock:
            self.closing = True
            self.lock.notify_all()
        self.server.shutdown()
        self.server.server_close()

    def wait_for_subscribers(self, count=1, timeout_s=5.0):
        """Wait until `count` event streams are open: what is published from then on reaches
        them. False after `timeout_s`."""
        with self.lock:
            return self.lock.wait_for(lambda: self.subscribers >= count, timeout_s)

    def publish(self, type_, device=None, **fields):
        with self.lock:
            seq = len(self.events) + 1
            event = {"seq": seq, "time_ms": self.clock["now_ms"], "type": type_, "device": device}
            event.update(fields)
            self.events.append(event)
            self.lock.notify_all()

    # ---- routes: each returns (status, body) ----

    def route(self, method, path, query, body):
        parts = [p for p in path.split("/") if p][1:]   # drop "api"
        if parts == ["rig"] and method == "GET":
            return 200, {"clock": self.clock, "devices": [
                {"name": d["name"], "protocol": d["protocol"], "model": d["model"], "firmware": d["firmware"],
                 "tcp": d["endpoints"]["tcp"], "pty": d["endpoints"]["pty"]} for d in self.devices.values()]}
        if parts == ["clock"]:
            return self.route_clock(method, body)
        if parts[:1] == ["devices"] and len(parts) >= 2:
            return self.route_device(method, parts[1:], query, body)
        if parts[:1] == ["faults"]:
            return self.route_faults(method, parts[1:], body)
        if parts[:1] == ["frames"] and len(parts) <= 2 and method == "GET":
            if len(parts) == 1:
                return 200, self.frames
            for frame in self.frames["frames"] + self.frames["tools"]:
                if frame["name"] == parts[1]:
                    return 200, frame
            return 404, {"error": f"no frame named \"{parts[1]}\""}
        if parts == ["reset"] and method == "POST":
            self.faults.clear()
            for name in self.logs:
                self.logs[name] = []
            self.publish("reset", keep_saved=body.get("keep_saved", True))
            return 200, {"reset": list(self.devices), "now_ms": self.clock["now_ms"]}
        return 404, {"error": f"no route {path!r}"}

    def route_clock(self, method, body):
        if method == "GET":
            return 200, self.clock
        if len(body) != 1 and "run_until_idle" not in body:
            return 400, {"error": "expected exactly one of pause, resume, step_ms, scale, run_until_idle"}
        clock = self.clock
        if "pause" in body:
            clock["paused"] = True
        elif "resume" in body:
            clock["paused"] = False
        elif "step_ms" in body:
            if not isinstance(body["step_ms"], int) or body["step_ms"] < 0:
                return 400, {"error": f"\"step_ms\": expected an integer 0..86400000, got {body['step_ms']}"}
            clock["now_ms"] += body["step_ms"]
        elif "scale" in body:
            clock["time_scale"] = float(body["scale"])
        elif "run_until_idle" in body:
            ran = 10.0
            if self.busy_ms is not None:   # something that moves for busy_ms more of clock time
                ran = min(self.busy_ms, body["max_ms"])
                self.busy_ms -= ran
            clock["now_ms"] += ran
            clock["now_ticks"] = int(clock["now_ms"])
            return 200, dict(clock, reached_ms=clock["now_ms"], idle=not self.busy_ms)
        clock["now_ticks"] = int(clock["now_ms"])
        return 200, clock

    def route_device(self, method, parts, query, body):
        device = self.devices.get(parts[0])
        if device is None:
            return 404, {"error": f"no device \"{parts[0]}\""}
        if len(parts) == 1 and method == "GET":
            return 200, dict(device, faults=[f for f in self.faults.values() if f["device"] == parts[0]])
        if len(parts) == 3 and parts[1] == "channels" and method == "PATCH":
            index = int(parts[2])
            if index >= len(device["channels"]):
                return 404, {"error": f"no channel {index} on \"{parts[0]}\""}
            for key in body:
                if key not in ("position_si", "referenced", "limit_switch", "sensor"):
                    return 400, {"error": f"unknown key \"{key}\""}
            device["channels"][index].update(body)
            return 200, device["channels"][index]
        if len(parts) == 2 and parts[1] == "log":
            if method == "DELETE":
                self.logs[parts[0]] = []
                return 200, {"device": parts[0], "cleared": True}
            entries = self.logs[parts[0]]
            if parts[0] == self.acks_on_poll and "last" not in query:
                entries.append({"seq": entries[-1]["seq"] + 1 if entries else 1, "time_ms": self.clock["now_ms"],
                                "direction": "in", "peer": "tcp", "hex": "92 04 00 00 50 01",
                                "decoded": {"id": "0x0492", "name": "MGMSG_MOT_ACK_DCSTATUSUPDATE"}, "notes": []})
            if "last" in query:
                entries = entries[-int(query["last"][0]):]
            return 200, {"device": parts[0], "capacity": 1000, "entries": entries}
        return 405, {"error": f"{method} /api/devices/{'/'.join(parts)}: method not allowed"}

    def route_faults(self, method, parts, body):
        if not parts and method == "GET":
            return 200, {"faults": list(self.faults.values())}
        if not parts and method == "DELETE":
            removed = list(self.faults)
            self.faults.clear()
            return 200, {"removed": removed}
        if not parts and method == "POST":
            if body.get("device") not in self.devices:
                return 404, {"error": f"no device \"{body.get('device')}\""}
            params = {k: v for k, v in body.items() if k not in ("device", "channel", "kind")}
            fault = {"id": self.next_fault_id, "device": body["device"], "channel": body.get("channel", 0),
                     "kind": body["kind"], "params": params,
                     "active": body["kind"] not in self.ONE_OFF, "since_ms": self.clock["now_ms"]}
            self.next_fault_id += 1
            if fault["active"]:
                self.faults[fault["id"]] = fault
            self.publish("fault_added", body["device"], fault=fault)
            return 201, fault
        if len(parts) == 1 and method == "DELETE":
            fault = self.faults.pop(int(parts[0]), None)
            if fault is None:
                return 404, {"error": f"no fault {parts[0]}"}
            self.publish("fault_removed", fault["device"], id=fault["id"])
            return 200, {"id": fault["id"], "removed": True}
        return 405, {"error": "method not allowed"}


def _handler(fake):
    class Handler(BaseHTTPRequestHandler):
        protocol_version = "HTTP/1.0"

        def log_message(self, *args):
            pass

        def do_any(self):
            url = urllib.parse.urlsplit(self.path)
            length = int(self.headers.get("Content-Length") or 0)
            raw = self.rfile.read(length) if length else b""
            body = json.loads(raw) if raw else {}
            fake.requests.append((self.command, self.path, body))
            fake.headers.append(self.headers)
            if url.path == "/api/events" and self.command == "GET":
                return self.stream(urllib.parse.parse_qs(url.query))
            with fake.lock:
                status, answer = fake.route(self.command, url.path, urllib.parse.parse_qs(url.query), body)
            data = json.dumps(answer).encode()
            self.send_response(status)
            self.send_header("Content-Type", "application/json")
            self.send_header("Content-Length", str(len(data)))
            self.end_headers()
            self.wfile.write(data)

        do_GET = do_POST = do_PATCH = do_DELETE = do_PUT = do_any

        def stream(self, query):
            wanted = set(",".join(query.get("device", [])).split(",")) - {""}
            types = set(",".join(query.get("type", [])).split(",")) - {""}
            # Subscribed before the answer's headers go out: once the client's events() returned,
            # wait_for_subscribers() sees it. Live only, as rigsimd: nothing published before.
            with fake.lock:
                sent = len(fake.events)
                fake.subscribers += 1
                fake.lock.notify_all()
            try:
                self.send_response(200)
                self.send_header("Content-Type", "text/event-stream")
                self.end_headers()
                self.wfile.write(b": hello\n\n")
                self.wfile.flush()
                while True:
                    with fake.lock:
                        while sent == len(fake.events) and not fake.closing:
                            fake.lock.wait(0.5)
                        if fake.closing:
                            return
                        pending = fake.events[sent:]
                        sent = len(fake.events)
                    for e in pending:
                        if wanted and e.get("device") not in wanted:
                            continue
                        if types and e["type"] not in types:
                            continue
                        self.wfile.write(f"event: {e['type']}\nid: {e['seq']}\ndata: {json.dumps(e)}\n\n".encode())
                    self.wfile.flush()
            except OSError:
                return
            finally:
                with fake.lock:
                    fake.subscribers -= 1
                    fake.lock.notify_all()

    return Handler
