"""A small Thorlabs APT client for a DC servo K-Cube (KDC101) over pyserial, written as a
driver author would (APT protocol: MOT_MOVE_HOME / MOVE_HOMED p.41, MOT_MOVE_ABSOLUTE p.45,
MOT_REQ/GET_DCSTATUSUPDATE p.79, HW_RICHRESPONSE p.13). Little-endian throughout."""

import struct
import time

import serial

HOST, UNIT = 0x01, 0x50
MOVE_HOME, MOVE_HOMED = 0x0443, 0x0444
MOVE_ABSOLUTE, MOVE_COMPLETED, MOVE_STOPPED = 0x0453, 0x0464, 0x0466
REQ_DCSTATUSUPDATE, GET_DCSTATUSUPDATE = 0x0490, 0x0491
HW_RESPONSE, HW_RICHRESPONSE = 0x0080, 0x0081

HOMING, HOMED = 0x00000200, 0x00000400
MOTION_ERROR, CURRENT_LIMIT = 0x00004000, 0x01000000


class AptError(Exception):
    """The controller reported a fault (HW_RESPONSE / HW_RICHRESPONSE) or an error status."""

    def __init__(self, message, status=None, code=None):
        super().__init__(message)
        self.status = status
        self.code = code


class AptClient:
    def __init__(self, port, timeout_s=2.0, channel=1):
        self.port = serial.serial_for_url(port, baudrate=115200, timeout=timeout_s)
        self.channel = channel
        self.faults = []   # (code, notes) of fault reports received
        self.pending = []  # messages received while waiting for another one, in order

    def close(self):
        self.port.close()

    def _send(self, message_id, p1=0, p2=0, data=None):
        if data is None:
            self.port.write(struct.pack("<HBBBB", message_id, p1, p2, UNIT, HOST))
        else:
            self.port.write(struct.pack("<HHBB", message_id, len(data), UNIT | 0x80, HOST) + data)

    def _read(self, n):
        data = self.port.read(n)
        if len(data) != n:
            raise TimeoutError(f"expected {n} bytes from the controller, got {len(data)}")
        return data

    def receive(self):
        """One message: (id, data or the two parameter bytes)."""
        header = self._read(6)
        message_id, length = struct.unpack_from("<HH", header)
        if header[4] & 0x80:
            data = self._read(length)
        else:
            data = header[2:4]
        if message_id == HW_RICHRESPONSE:
            _, code = struct.unpack_from("<HH", data)
            self.faults.append((code, data[4:].split(b"\0")[0].decode("ascii", "replace")))
        elif message_id == HW_RESPONSE:
            self.faults.append((None, "HW_RESPONSE"))
        return message_id, data

    def wait_for(self, *ids, timeout_s=60.0):
        """The next message with one of `ids`. Others met meanwhile are kept for a later
        wait_for: a move can end (MOVE_STOPPED) before the status answer asked after it."""
        for i, (message_id, data) in enumerate(self.pending):
            if message_id in ids:
                del self.pending[i]
                return message_id, data
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            try:
                message_id, data = self.receive()
            except TimeoutError:
                continue
            if message_id in ids:
                return message_id, data
            if message_id in (MOVE_HOMED, MOVE_COMPLETED, MOVE_STOPPED):
                self.pending.append((message_id, data))
        raise TimeoutError(f"none of {[hex(i) for i in ids]} within {timeout_s} s")

    def status(self):
        """(position counts, status bits) from MOT_REQ_DCSTATUSUPDATE."""
        self._send(REQ_DCSTATUSUPDATE, self.channel)
        _, data = self.wait_for(GET_DCSTATUSUPDATE, timeout_s=5)
        _, position, _, _, bits = struct.unpack("<HiHHI", data)
        return position, bits

    def home(self):
        """Start homing. The status request after it returns once the unit has taken the
        MOVE_HOME (it answers in order), so the caller knows homing has begun."""
        self._send(MOVE_HOME, self.channel)
        return self.status()

    def wait_homed(self, timeout_s=60.0):
        self.wait_for(MOVE_HOMED, timeout_s=timeout_s)

    def move_absolute(self, position_counts):
        self._send(MOVE_ABSOLUTE, data=struct.pack("<Hi", self.channel, position_counts))
        return self.status()

    def wait_move(self, timeout_s=60.0):
        """Wait for the end of the move; raise AptError if it ended in a fault."""
        message_id, data = self.wait_for(MOVE_COMPLETED, MOVE_STOPPED, timeout_s=timeout_s)
        _, position, _, _, bits = struct.unpack("<HiHHI", data)
        if bits & (MOTION_ERROR | CURRENT_LIMIT) or self.faults:
            code, notes = self.faults[-1] if self.faults else (None, "")
            raise AptError(f"move stopped at {position} with status {bits:#010x}: {notes}",
                           status=bits, code=code)
        return position
