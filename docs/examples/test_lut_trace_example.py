"""A LUT waveform on a BPC303 piezo bay (bpc303_rig.json), loaded over the APT wire as a client
would (PZ_SET_OUTPUTLUT p.106, PZ_SET_OUTPUTLUTPARAMS p.108, PZ_START_LUTOUTPUT p.112), started
by a pulse on the bay's TRIG IN through the control API, and checked through its trace
(docs/control-api.md#traces): one sample per 1 ms tick, each the table's value."""

import math
import struct

import serial

HOST, BAY1 = 0x01, 0x21
SET_OUTPUTLUT, SET_OUTPUTLUTPARAMS, REQ_OUTPUTLUTPARAMS, GET_OUTPUTLUTPARAMS = 0x0700, 0x0703, 0x0704, 0x0705
START_LUTOUTPUT = 0x0706
FIXED, INPUT_TRIG, INPUT_TRIG_SENSE_HI = 0x02, 0x08, 0x20   # OUTPUTLUTPARAMS mode bits (p.108)

# 100 samples of one sine period around half the 150 V range, as output codes (32767 = 150 V).
TABLE = [round(16384 + 12000 * math.sin(2 * math.pi * k / 100)) for k in range(100)]


def send(port, message_id, data):
    port.write(struct.pack("<HHBB", message_id, len(data), BAY1 | 0x80, HOST) + data)


def load_and_arm(port):
    for index, value in enumerate(TABLE):
        send(port, SET_OUTPUTLUT, struct.pack("<HHh", 1, index, value))
    # Fixed mode, 1 cycle of 100 samples, DelayTime 1 (1 ms on a BPC, p.109), no rests, started by
    # the rising edge of TRIG IN.
    params = struct.pack("<HHHiiiiHiH", 1, FIXED | INPUT_TRIG | INPUT_TRIG_SENSE_HI, len(TABLE), 1, 1, 0, 0, 0, 0, 0)
    send(port, SET_OUTPUTLUTPARAMS, params)
    port.write(struct.pack("<HBBBB", START_LUTOUTPUT, 1, 0, BAY1, HOST))   # with INPUTTRIG: arms
    # The answer to a request shows the unit has handled everything before it.
    port.write(struct.pack("<HBBBB", REQ_OUTPUTLUTPARAMS, 1, 0, BAY1, HOST))
    answer = port.read(6 + 30)
    assert struct.unpack_from("<H", answer)[0] == GET_OUTPUTLUTPARAMS
    assert answer[6 + 2:6 + 4] == params[2:4]


def test_a_triggered_lut_run_follows_the_table_in_the_trace(piezo_rig):
    bay = piezo_rig.device("bpc303")
    port = serial.serial_for_url(piezo_rig.endpoint("bpc303").url, timeout=5)
    try:
        load_and_arm(port)
    finally:
        port.close()
    assert bay.channel(0)["lut"]["armed"]

    started = piezo_rig.clock()["now_ticks"]
    bay.trigger(0)
    piezo_rig.step(150)   # the run (100 ms) and some of the held value after it

    samples = [s for s in bay.trace(0, since=started) if s.lut_index is not None]
    assert [s.lut_index for s in samples] == list(range(100))
    assert [s.tick - started for s in samples] == list(range(100))   # 1 ms per sample
    assert [s.output_code for s in samples] == TABLE
    for s in samples:
        assert math.isclose(s.output_v, s.output_code / 32767 * 150, rel_tol=1e-9)
    assert bay.channel(0)["output_code"] == TABLE[-1]   # the last value holds
