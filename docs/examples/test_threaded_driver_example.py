"""A driver with a thread of its own against rigsim's KDC101 (kdc101 of the default rig), on a
paused clock (docs/python.md "Drivers with a thread of their own").

ThreadedKdc works as pyLabLib's and thorlabs_apt_device's drivers do: a background thread sends
what the test asks for, reads every message the unit sends, and acknowledges status updates on a
wall-clock period (MOT_ACK_DCSTATUSUPDATE, the "server alive" message: a USB unit stops its
updates after 50 without one, APT protocol p. 80). Two things then differ from a driver that
does everything on the test's own thread:

1. The command is sent when the driver's thread gets to it. A run_until_idle() that reaches the
   daemon first finds nothing moving and returns at once; wait_for_message() waits until the
   unit received the command.
2. Seconds of clock time run in one go outrun the driver's wall-clock acknowledgements: the unit
   cuts its status updates off. run_until_idle(chunk_ms=..., wait_for=(device, ack)) runs the
   clock in pieces and lets the driver acknowledge between them.
"""

import os
import queue
import socket
import struct
import threading
import time

import pytest

HOST, UNIT = 0x01, 0x50
HW_START_UPDATEMSGS = 0x0011
MOVE_HOME, MOVE_HOMED = 0x0443, 0x0444
GET_DCSTATUSUPDATE, ACK_DCSTATUSUPDATE = 0x0491, 0x0492

pytestmark = pytest.mark.skipif(os.environ.get("RIGSIM_REAL_TIME") == "1",
                                reason="about a stepped clock: in real time the driver keeps up by itself")


class ThreadedKdc:
    """A KDC101 driver whose thread owns the socket."""

    def __init__(self, address, ack_period_s=0.05):
        self.sock = socket.create_connection(address, timeout=5)
        self.sock.settimeout(0.005)
        self.ack_period_s = ack_period_s
        self.commands = queue.Queue()
        self.updates = 0
        self.updated = threading.Condition()   # notified at each status update read
        self.homed = threading.Event()
        self.stopping = threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)
        self.thread.start()

    def send(self, message_id):
        """Queue a header-only command for channel 1; the thread sends it."""
        self.commands.put(struct.pack("<HBBBB", message_id, 1, 0, UNIT, HOST))

    def wait_for_updates(self, count, timeout_s=5.0):
        """Wait until the thread has read `count` status updates; False after `timeout_s`."""
        with self.updated:
            return self.updated.wait_for(lambda: self.updates >= count, timeout_s)

    def close(self):
        self.stopping.set()
        self.thread.join(5)
        self.sock.close()

    def _run(self):
        pending = b""
        next_ack = time.monotonic() + self.ack_period_s
        while not self.stopping.is_set():
            while not self.commands.empty():
                self.sock.sendall(self.commands.get())
            if time.monotonic() >= next_ack:
                self.sock.sendall(struct.pack("<HBBBB", ACK_DCSTATUSUPDATE, 0, 0, UNIT, HOST))
                next_ack += self.ack_period_s
            try:
                data = self.sock.recv(4096)
            except socket.timeout:
                continue
            if not data:
                return
            pending = self._take(pending + data)

    def _take(self, pending):
        while len(pending) >= 6:
            message_id, length = struct.unpack_from("<HH", pending)
            size = 6 + (length if pending[4] & 0x80 else 0)
            if len(pending) < size:
                break
            if message_id == GET_DCSTATUSUPDATE:
                with self.updated:
                    self.updates += 1
                    self.updated.notify_all()
            elif message_id == MOVE_HOMED:
                self.homed.set()
            pending = pending[size:]
        return pending


@pytest.fixture
def driver(rig):
    d = ThreadedKdc(rig.endpoint("kdc101").address)
    yield d
    d.close()


def test_wait_until_the_drivers_thread_has_sent_its_command(rig, driver):
    cursor = rig.log_cursor("kdc101")
    driver.send(MOVE_HOME)   # queued: the driver's thread sends it when it gets to it
    rig.wait_for_message("kdc101", "MOT_MOVE_HOME", after=cursor)
    answer = rig.run_until_idle(600_000)   # raises NotIdle if the homing were still going at the limit
    assert answer["idle"] is True
    assert answer["reached_ms"] > 1000     # the homing took clock time: it had started
    assert driver.homed.wait(5)
    with pytest.raises(TimeoutError, match="kdc101 received no MOT_MOVE_STOP"):
        rig.wait_for_message("kdc101", "MOT_MOVE_STOP", after=cursor, timeout_s=0.1)


def test_a_clock_run_in_pieces_keeps_the_drivers_status_updates(rig, driver):
    driver.send(HW_START_UPDATEMSGS)
    cursor = rig.log_cursor("kdc101")
    driver.send(MOVE_HOME)
    rig.wait_for_message("kdc101", "MOT_MOVE_HOME", after=cursor)
    start = rig.clock()["now_ms"]
    answer = rig.run_until_idle(600_000, chunk_ms=1000, wait_for=("kdc101", "MOT_ACK_DCSTATUSUPDATE"))
    assert driver.homed.wait(5)
    homing_ms = answer["reached_ms"] - start
    assert homing_ms > 2000
    notes = [n for e in rig.log("kdc101")["entries"] for n in e["notes"]]
    assert not [n for n in notes if n.startswith("cut-off")]
    driver.wait_for_updates(homing_ms / 100 - 1)   # the last piece's may still be on their way
    assert driver.updates >= homing_ms / 100 - 1   # one every 100 ms of clock, all the way


def test_a_clock_run_in_one_go_outruns_the_drivers_acknowledgements(rig, driver):
    driver.send(HW_START_UPDATEMSGS)
    cursor = rig.log_cursor("kdc101")
    driver.send(MOVE_HOME)
    rig.wait_for_message("kdc101", "MOT_MOVE_HOME", after=cursor)
    rig.run_until_idle(600_000)   # tens of seconds of clock in a few milliseconds of wall time
    notes = [n for e in rig.log("kdc101")["entries"] for n in e["notes"]]
    assert [n for n in notes if n.startswith("cut-off: 50 status update messages")]
