#!/usr/bin/env python3
"""The live view (docs/control-api.md#the-live-view) in Debian's headless Chromium, driven through
chromedriver's WebDriver protocol (W3C; standard library HTTP, no Selenium): the page, opened with
the daemon's token in its fragment, shows the fibre-alignment rig; a KDC101 move sent over the APT
wire changes the position on the page (from the event stream and the page's polling, the page never
reloaded); then, with the piezo's LUT running and a stage moving, a screenshot is stored as a test
artefact.

  live_view_browser.py --rigsimd BUILD/rigsimd --rig config/examples/fibre_alignment.json --out DIR

Needs /usr/bin/chromium and /usr/bin/chromedriver (Debian's chromium and chromium-driver:
scripts/deps.sh --test). Waits are bounded polls in wall time (a browser runs in wall time); what is
asserted is what the page shows, never how long it took."""

import argparse
import base64
import json
import math
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

from rigsim import Rigsim

HOST, UNIT = 0x01, 0x50
MOVE_ABSOLUTE, SET_OUTPUTLUT, SET_OUTPUTLUTPARAMS, START_LUTOUTPUT = 0x0453, 0x0700, 0x0703, 0x0706
REQ_OUTPUTLUTPARAMS, GET_OUTPUTLUTPARAMS = 0x0704, 0x0705
Z8_COUNTS_PER_MM = 34304   # config/stages/Z825B.json


def frame(message_id, data):
    return struct.pack("<HHBB", message_id, len(data), UNIT | 0x80, HOST) + data


def apt_send(endpoint, payload, answer_bytes=0):
    with socket.create_connection(endpoint.address, timeout=5) as s:
        s.sendall(payload)
        answer = b""
        while len(answer) < answer_bytes:
            chunk = s.recv(answer_bytes - len(answer))
            if not chunk:
                break
            answer += chunk
        return answer


def move_absolute(rig, device, mm):
    apt_send(rig.endpoint(device), frame(MOVE_ABSOLUTE, struct.pack("<Hi", 1, round(mm * Z8_COUNTS_PER_MM))))


def start_lut(rig, device):
    """A continuous sine on the TPZ001 (PZ_SET_OUTPUTLUT p.106, PZ_SET_OUTPUTLUTPARAMS p.108, mode 1
    continuous, 100 samples, DelayTime 20 x 0.25 ms)."""
    table = [round(16384 + 12000 * math.sin(2 * math.pi * k / 100)) for k in range(100)]
    payload = b"".join(frame(SET_OUTPUTLUT, struct.pack("<HHh", 1, i, v)) for i, v in enumerate(table))
    payload += frame(SET_OUTPUTLUTPARAMS, struct.pack("<HHHiiiiHiH", 1, 0x01, len(table), 0, 20, 0, 0, 0, 0, 0))
    payload += struct.pack("<HBBBB", START_LUTOUTPUT, 1, 0, UNIT, HOST)
    payload += struct.pack("<HBBBB", REQ_OUTPUTLUTPARAMS, 1, 0, UNIT, HOST)
    answer = apt_send(rig.endpoint(device), payload, 6 + 30)
    assert struct.unpack_from("<H", answer)[0] == GET_OUTPUTLUTPARAMS, answer


class WebDriver:
    """The few W3C WebDriver commands this test needs, over chromedriver's HTTP."""

    def __init__(self, chromedriver, chromium, log_path):
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.port = s.getsockname()[1]
        self.log = open(log_path, "wb")
        self.process = subprocess.Popen([chromedriver, f"--port={self.port}"], stdout=self.log, stderr=self.log)
        self.base = f"http://127.0.0.1:{self.port}"
        self._wait(lambda: self._call("GET", "/status").get("ready"), 20, "chromedriver ready")
        # --remote-debugging-pipe: chromedriver talks to the browser over a pipe, not a "localhost"
        # port (a root without /etc/hosts resolved it elsewhere: "unable to connect to renderer").
        args = ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--remote-debugging-pipe",
                "--window-size=1500,1150", "--hide-scrollbars", "--force-device-scale-factor=1"]
        caps = {"capabilities": {"alwaysMatch": {"browserName": "chrome",
                                                 "goog:chromeOptions": {"binary": chromium, "args": args}}}}
        self.session = self._call("POST", "/session", caps)["sessionId"]

    def _call(self, method, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(self.base + path, data=data, method=method,
                                         headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(request, timeout=60) as answer:
                return json.load(answer)["value"]
        except urllib.error.HTTPError as e:
            raise RuntimeError(f"WebDriver {method} {path}: {e.code} {e.read()[:500]!r}") from None
        except urllib.error.URLError:
            if method == "GET" and path == "/status":
                return {}
            raise

    @staticmethod
    def _wait(condition, timeout_s, what):
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            value = condition()
            if value:
                return value
            time.sleep(0.1)
        raise AssertionError(f"timed out waiting for {what}")

    def call(self, method, path, body=None):
        return self._call(method, f"/session/{self.session}{path}", body)

    def go(self, url):
        self.call("POST", "/url", {"url": url})

    def script(self, source, *args):
        return self.call("POST", "/execute/sync", {"script": source, "args": list(args)})

    def wait_for(self, source, timeout_s, what, *args):
        return self._wait(lambda: self.script(source, *args), timeout_s, what)

    def screenshot(self, path):
        with open(path, "wb") as f:
            f.write(base64.b64decode(self.call("GET", "/screenshot")))

    def quit(self):
        try:
            self.call("DELETE", "")
        finally:
            self.process.terminate()
            self.process.wait(10)
            self.log.close()


POSITION = "const e = document.getElementById(arguments[0]); return e ? e.dataset.si : null;"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rigsimd", required=True)
    parser.add_argument("--rig", required=True)
    parser.add_argument("--out", required=True, help="directory for the screenshot and the logs")
    parser.add_argument("--chromium", default="/usr/bin/chromium")
    parser.add_argument("--chromedriver", default="/usr/bin/chromedriver")
    args = parser.parse_args()
    for program in (args.chromium, args.chromedriver):
        if not shutil.which(program):
            print(f"live_view_browser: {program} is missing: scripts/deps.sh --test installs Debian's chromium "
                  "and chromium-driver", file=sys.stderr)
            return 1
    os.makedirs(args.out, exist_ok=True)
    profile = tempfile.mkdtemp(prefix="rigsim-chromium-")
    os.environ["HOME"] = profile   # Chromium's profile and caches, not the user's
    with Rigsim(args.rig, rigsimd=args.rigsimd) as rig:
        driver = WebDriver(args.chromedriver, args.chromium, os.path.join(args.out, "chromedriver.log"))
        try:
            driver.go(f"{rig.control.url}/#token={rig.token}")
            driver.wait_for("return document.body.dataset.ready === 'true';", 30, "the page to read the rig")
            before = driver.script(POSITION, "pos-coarse_x-0")
            print("coarse_x on the page before the move:", before)
            assert before not in (None, ""), before
            start_si = float(before)   # the stage's physical start; its counter reads 0 there
            assert driver.script("return document.querySelectorAll('#chain circle').length;") >= 8
            assert driver.wait_for("return document.getElementById('connection').textContent === 'live';", 30,
                                   "the event stream")

            move_absolute(rig, "coarse_x", 1.0)
            rig.run_until_idle(max_ms=60_000)
            after = driver.wait_for(
                "const v = document.getElementById(arguments[0]).dataset.si;"
                "return Math.abs(Number(v) - arguments[1]) < 1e-6 ? v : null;", 30,
                "the page to show coarse_x 1 mm further", "pos-coarse_x-0", start_si + 0.001)
            print("coarse_x on the page after the move:", after)
            status = driver.script("return document.getElementById('status-coarse_x-0').textContent;")
            print("coarse_x status words:", status)
            assert status, "no status words for coarse_x"

            # A moving rig for the picture: the piezo's LUT running, a stage on its way 6 mm further.
            start_lut(rig, "fine_x")
            move_absolute(rig, "coarse_x", 6.0)
            driver.wait_for("return document.querySelector('#pos-coarse_x-0.moving') !== null;", 30,
                            "coarse_x shown moving")
            driver.wait_for("return document.querySelectorAll('svg.lut polyline').length === 2;", 30,
                            "the LUT waveform")
            time.sleep(1.5)   # some trajectory on the plot
            driver.wait_for("return document.querySelector('#wire li') !== null;", 30, "wire entries")
            assert driver.script("return document.querySelectorAll('#fault-kinds button').length;") == 19
            shot = os.path.join(args.out, "live-view.png")
            driver.screenshot(shot)
            print("screenshot:", shot, os.path.getsize(shot), "bytes")

            # The fault buttons: a stage's fault on the chosen channel, a wire fault with the typed
            # parameters; each listed, in the daemon too, and removed by its button.
            click = "document.querySelector(arguments[0]).click(); return true;"
            driver.script("document.getElementById('fault-device').value = 'coarse_y';"
                          "document.getElementById('fault-params').value = '{}'; return true;")
            driver.script(click, "#fault-kinds [data-kind=stall]")
            driver.wait_for("return document.querySelectorAll('#fault-list li').length === 1;", 30, "the stall listed")
            driver.script("document.getElementById('fault-params').value = '{\"latency_ms\": 20}'; return true;")
            driver.script(click, "#fault-kinds [data-kind=latency]")
            driver.wait_for("return document.querySelectorAll('#fault-list li').length === 2;", 30, "the latency listed")
            message = driver.script("return document.getElementById('message').textContent;")
            assert message == "", message
            faults = rig.faults()
            print("faults injected from the page:", [(f["kind"], f["device"], f["channel"], f["params"]) for f in faults])
            assert sorted((f["kind"], f["device"], f["channel"]) for f in faults) == \
                [("latency", "coarse_y", None), ("stall", "coarse_y", 0)], faults
            assert [f["params"] for f in faults if f["kind"] == "latency"] == [{"latency_ms": 20}], faults
            for left in (1, 0):
                driver.script(click, "#fault-list li button")
                driver.wait_for("return document.querySelectorAll('#fault-list li').length === arguments[0];", 30,
                                f"{left} fault(s) listed", left)
            assert rig.faults() == []
        except Exception:
            # What the page says, for the log of a failure.
            try:
                print("page message:", driver.script("return document.getElementById('message').textContent;"))
                print("page connection:", driver.script("return document.getElementById('connection').textContent;"))
                driver.screenshot(os.path.join(args.out, "live-view-failed.png"))
            except Exception as e:   # the browser itself may be what failed
                print("no page state:", e)
            raise
        finally:
            driver.quit()
            shutil.rmtree(profile, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
