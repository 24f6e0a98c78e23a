"""A client of rigsimd's HTTP control API (docs/control-api.md), urllib only."""

import json
import urllib.error
import urllib.request


class ControlError(Exception):
    """The control API answered with an error: `status` (4xx) and its `message`."""

    def __init__(self, status, message):
        super().__init__(f"{status}: {message}")
        self.status = status
        self.message = message


class ControlClient:
    """The routes of the control API at `url` ("http://127.0.0.1:PORT")."""

    def __init__(self, url, timeout_s=10.0):
        self.url = url.rstrip("/")
        self.timeout_s = timeout_s

    def request(self, method, path, body=None):
        """One request; returns the decoded JSON answer or raises ControlError."""
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.url + path, data=data, method=method)
        if data is not None:
            req.add_header("Content-Type", "application/json")
        try:
            with urllib.request.urlopen(req, timeout=self.timeout_s) as answer:
                return json.loads(answer.read() or b"null")
        except urllib.error.HTTPError as e:
            text = e.read().decode(errors="replace")
            try:
                message = json.loads(text).get("error", text)
            except (ValueError, AttributeError):
                message = text
            raise ControlError(e.code, message) from None

    def rig(self):
        """GET /api/rig: the devices and the clock."""
        return self.request("GET", "/api/rig")

    def clock(self):
        """GET /api/clock."""
        return self.request("GET", "/api/clock")

    def pause(self):
        return self.request("POST", "/api/clock", {"pause": True})

    def resume(self):
        return self.request("POST", "/api/clock", {"resume": True})

    def step(self, ms):
        """Advance the clock `ms` milliseconds now (paused or running)."""
        return self.request("POST", "/api/clock", {"step_ms": ms})

    def scale(self, factor):
        """Run the clock `factor` times faster than wall time from now on."""
        return self.request("POST", "/api/clock", {"scale": factor})

    def run_until_idle(self, max_ms):
        """Advance as fast as the CPU allows until nothing moves, at most `max_ms` of clock time."""
        return self.request("POST", "/api/clock", {"run_until_idle": True, "max_ms": max_ms})
