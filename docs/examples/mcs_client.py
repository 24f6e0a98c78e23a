"""A small SmarAct MCS client over pyserial, written as a driver author would (MCS ASCII
interface manual: 2.1 communication modes, 3.3 MPA/GP/GS, 4.1 status codes, 4.2 error codes).

Works on a real serial port ("/dev/ttyUSB0") or any pyserial URL ("socket://127.0.0.1:40100").
"""

import time

import serial

STOPPED, HOLDING, TARGETING = 0, 3, 4
END_STOP_REACHED = 142


class McsError(Exception):
    """The controller answered E<channel>,<code> with a non-zero code."""

    def __init__(self, channel, code):
        super().__init__(f"MCS channel {channel}: error {code}")
        self.channel = channel
        self.code = code


class McsClient:
    def __init__(self, port, timeout_s=2.0):
        self.port = serial.serial_for_url(port, baudrate=9600, timeout=timeout_s)
        self.asynchronous = False
        self.errors = []   # (channel, code) reported unprompted in asynchronous mode

    def close(self):
        self.port.close()

    def _read_line(self):
        line = self.port.readline().decode("ascii")
        if not line.endswith("\n"):
            raise TimeoutError(f"no answer from the controller (got {line!r})")
        return line.strip()

    def ask(self, command, answer_prefix=None):
        """Send ':command'; return the first answer line starting with `answer_prefix` (or the
        first line at all). Unprompted errors met meanwhile are kept in `errors`."""
        self.port.write(f":{command}\n".encode("ascii"))
        while True:
            line = self._read_line()
            if answer_prefix is None or line.startswith(":" + answer_prefix):
                return line[1:]
            if line.startswith(":E"):
                channel, code = (int(x) for x in line[2:].split(","))
                self.errors.append((channel, code))

    def _acknowledged(self, command, channel):
        answer = self.ask(command, "E")
        code = int(answer.split(",")[1])
        if code != 0:
            raise McsError(channel, code)

    def set_asynchronous(self):
        """SCM1: acknowledges are omitted; errors such as 142 (end stop) arrive unprompted.
        SCM is answered in the new mode, that is not at all: GCM confirms the switch."""
        self.port.write(b":SCM1\n")
        if self.ask("GCM", "CM") != "CM1":
            raise McsError(-1, "communication mode not switched")
        self.asynchronous = True

    def position_nm(self, channel):
        answer = self.ask(f"GP{channel}", f"P{channel},")
        return int(answer.split(",")[1])

    def status(self, channel):
        return int(self.ask(f"GS{channel}", f"S{channel},").split(",")[1])

    def move_absolute(self, channel, position_nm, hold_ms=0):
        command = f"MPA{channel},{position_nm},{hold_ms}"
        if self.asynchronous:
            self.port.write(f":{command}\n".encode("ascii"))
            self.status(channel)   # answered after the move was taken: the move has started
        else:
            self._acknowledged(command, channel)

    def wait_stopped(self, channel, timeout_s=60.0):
        """Poll GS until the channel stops or holds; raise McsError for an error it reported."""
        deadline = time.monotonic() + timeout_s
        while True:
            status = self.status(channel)
            for error in self.errors:
                if error[0] == channel:
                    self.errors.remove(error)
                    raise McsError(*error)
            if status in (STOPPED, HOLDING):
                return status
            if time.monotonic() > deadline:
                raise TimeoutError(f"channel {channel} still moving (status {status})")
            time.sleep(0.01)
