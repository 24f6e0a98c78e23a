// MCS2 movements on the stepped clock (MCS2 Programmer's Guide 1.0.6, 2.6-2.12): the move modes,
// velocity, acceleration and stop, hold time, end stops and the range limit, the preconditions,
// calibration, referencing of each kind, and the channel state word and error they leave.

#include "mcs2_harness.hpp"

#include <catch2/catch.hpp>

#include <string>

using rigsim::test::Mcs2Harness;
using rigsim::test::mcs2_device_config;

namespace {

constexpr std::int64_t kMoving = 0x1, kClosedLoop = 0x2, kCalibrating = 0x4, kReferencing = 0x8, kDelayed = 0x10,
                       kSensor = 0x20, kCalibrated = 0x40, kReferenced = 0x80, kEndStop = 0x100, kRangeLimit = 0x200,
                       kFailed = 0x800, kMark = 0x8000;

std::int64_t state(Mcs2Harness& h, int channel = 0)
{
    return h.number(":CHAN" + std::to_string(channel) + ":STAT?");
}

std::int64_t activity(Mcs2Harness& h, int channel = 0)
{
    return state(h, channel) & 0x1f;
}

} // namespace

TEST_CASE("MCS2 closed-loop absolute move at a velocity: on time, then holding for ever by default", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:MMOD 0;VEL 1000000000;ACC 0");
    CHECK(h.send(":MOVE0 1000000000").empty());
    CHECK(activity(h) == (kMoving | kClosedLoop));
    CHECK(h.number(":CHAN0:POS:TARG?") == 1'000'000'000);
    h.advance_ms(500);
    CHECK(h.number(":CHAN0:POS?") == 500'000'000);
    h.advance_ms(501);
    CHECK(h.number(":CHAN0:POS?") == 1'000'000'000);
    CHECK(activity(h) == kClosedLoop);   // holding the target (2.6.7)
    h.advance_ms(60'000);
    CHECK(activity(h) == kClosedLoop);   // SA_CTL_INFINITE
    CHECK(h.ask(":CHAN0:ERR?") == "0");
    // Velocity 0: as fast as the stage goes (10 mm/s); hold time 200 ms, then stopped.
    h.send(":CHAN0:VEL 0;HOLD 200;:MOVE0 0");
    h.advance_ms(101);
    CHECK(h.number(":CHAN0:POS?") == 0);
    CHECK(activity(h) == kClosedLoop);
    h.advance_ms(200);
    CHECK(activity(h) == 0);
    h.send(":CHAN0:HOLD 0;:MOVE0 100000000");
    h.advance_ms(11);
    CHECK(activity(h) == 0);   // no holding at all
    CHECK(h.errors().empty());
}

TEST_CASE("MCS2 acceleration: a trapezoid, a first stop brakes and a second one stops hard", "[device][mcs2]")
{
    Mcs2Harness h;
    // 1 mm/s, 10 mm/s²: 0.1 s to full speed, 50 µm of ramp.
    h.send(":CHAN0:MMOD 0;VEL 1000000000;ACC 10000000000");
    h.send(":MOVE0 1000000000");
    h.advance_ms(100);
    CHECK(h.number(":CHAN0:POS?") == 50'000'000);
    h.advance_ms(400);
    CHECK(h.number(":CHAN0:POS?") == 450'000'000);
    h.send(":STOP0");   // brakes: 50 µm more in 0.1 s, still moving meanwhile
    CHECK(activity(h) == (kMoving | kClosedLoop));
    h.advance_ms(50);
    CHECK(h.number(":CHAN0:POS?") == 487'500'000);
    h.advance_ms(51);
    CHECK(h.number(":CHAN0:POS?") == 500'000'000);
    CHECK(activity(h) == 0);
    CHECK(h.ask(":CHAN0:ERR?") == "25");   // ABORTED (2.6.7)
    CHECK(h.ask(":CHAN0:ERR?") == "0");    // reading it resets it (4.10.1)
    h.send(":MOVE0 0");
    h.advance_ms(200);
    const auto at = h.number(":CHAN0:POS?");
    h.send(":STOP0;:STOP0");   // the second stop: hard
    CHECK(activity(h) == 0);
    CHECK(h.number(":CHAN0:POS?") == at);
}

TEST_CASE("MCS2 relative moves add to the target, or to the position with ACC_REL_POS_DIS, and 0 holds",
          "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:MMOD 1;VEL 1000000000");
    h.send(":MOVE0 1000000000");
    h.advance_ms(100);
    h.send(":MOVE0 1000000000");
    CHECK(h.number(":CHAN0:POS:TARG?") == 2'000'000'000);
    h.advance_ms(2'001);
    CHECK(h.number(":CHAN0:POS?") == 2'000'000'000);
    h.send(":CHAN0:PCON:OPT 1");   // Accumulate Relative Position Disabled (2.6.4)
    h.send(":MOVE0 1000000000");
    h.advance_ms(100);
    h.send(":MOVE0 1000000000");
    CHECK(h.number(":CHAN0:POS:TARG?") == 3'100'000'000);
    h.advance_ms(200);
    h.send(":MOVE0 0");   // abort and hold here (2.6.4)
    const auto here = h.number(":CHAN0:POS?");
    CHECK(activity(h) == kClosedLoop);
    h.advance_ms(1'000);
    CHECK(h.number(":CHAN0:POS?") == here);
}

TEST_CASE("MCS2 step mode: steps at the step frequency, amplitude scaling the step", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:MMOD 4;STEP:FREQ 1000");
    h.send(":MOVE0 100");
    CHECK(activity(h) == kMoving);   // open loop: no CLOSED_LOOP_ACTIVE
    h.advance_ms(50);
    CHECK(h.number(":CHAN0:POS?") == 50'000'000);
    h.advance_ms(51);
    CHECK(h.number(":CHAN0:POS?") == 100'000'000);
    CHECK(activity(h) == 0);
    h.send(":MOVE0 -100001");   // -100000 ... 100000 (4.4.8)
    CHECK(h.errors() == std::vector<std::string>{"19,\"Invalid parameter\""});
    CHECK((state(h) & kFailed) != 0);
}

TEST_CASE("MCS2 scan mode: the piezo goes to its 16-bit level at the scan velocity", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:MMOD 2;SCAN:VEL 65535");   // full range in one second
    h.send(":MOVE0 65535");
    CHECK(activity(h) == kMoving);
    h.advance_ms(500);
    CHECK(std::abs(h.number(":CHAN0:POS:SCAN?") - 32768) <= 16);
    h.advance_ms(501);
    CHECK(h.number(":CHAN0:POS:SCAN?") == 65535);
    CHECK(activity(h) == 0);
    CHECK(h.number(":CHAN0:POS?") == 1'500'000);   // the piezo's whole deflection
    h.send(":CHAN0:MMOD 3;:MOVE0 -70000");
    CHECK(h.errors() == std::vector<std::string>{"19,\"Invalid parameter\""});
}

TEST_CASE("MCS2 end stop and range limit: the state bit and the error until the next movement", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":MOVE0 20000000000");   // past the end stop at 10.5 mm
    h.advance_ms(1'100);
    CHECK(h.number(":CHAN0:POS?") == 10'500'000'000);
    CHECK((state(h) & (kEndStop | 0x1f)) == kEndStop);
    CHECK(h.ask(":CHAN0:ERR?") == "512");
    h.send(":MOVE0 0");
    CHECK((state(h) & kEndStop) == 0);   // "cleared by a new movement or stop command"
    h.advance_ms(1'100);
    h.send(":CHAN0:RLIM:MIN -1000000000;MAX 1000000000");   // MAX at the level of MIN (6.2.3)
    h.send(":MOVE0 2000000000");
    h.advance_ms(300);
    CHECK(h.number(":CHAN0:POS?") == 1'000'000'000);
    CHECK((state(h) & kRangeLimit) != 0);
    CHECK(h.ask(":CHAN0:ERR?") == "514");
    h.send(":STOP0");
    CHECK((state(h) & kRangeLimit) == 0);
}

TEST_CASE("MCS2 preconditions: amplifier, power supply, sensor and control-loop input", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:AMPL 0;:MOVE0 1000");
    CHECK((state(h) & kFailed) != 0);
    CHECK(h.ask(":CHAN0:ERR?") == "262");   // AMPLIFIER_DISABLED
    h.send(":CHAN0:AMPL 1;:MOD0:PSUP 0;:MOVE0 1000");
    CHECK(h.ask(":CHAN0:ERR?") == "261");   // POWER_SUPPLY_DISABLED
    h.send(":MOD0:PSUP 1;:CHAN0:SENS:PMOD 0;:MOVE0 1000");
    CHECK(h.ask(":CHAN0:ERR?") == "260");   // SENSOR_DISABLED
    h.send(":CHAN0:MMOD 4;:MOVE0 10");   // steps need no sensor
    CHECK(activity(h) == kMoving);
    h.advance_ms(20);
    h.send(":CHAN0:MMOD 0;SENS:PMOD 1;:CHAN0:CLIN 0;:MOVE0 1000");
    CHECK(h.ask(":CHAN0:ERR?") == "277");   // CONTROL_LOOP_INPUT_DISABLED
    h.send(":CHAN0:CLIN 2");
    // A movement that cannot start queues its error too (EPICS motorSmarAct clears a queued 260).
    CHECK(h.errors() == std::vector<std::string>{"262,\"Amplifier disabled\"", "261,\"Power supply disabled\"",
                                                 "260,\"Sensor disabled\"", "277,\"Control loop input disabled\"",
                                                 "257,\"No IO module present\""});
    h.send(":CHAN0:CLIN 1;:MOVE0 1000");
    CHECK((state(h) & kFailed) == 0);
}

TEST_CASE("MCS2 power save: a movement waits MOVE_DELAYED while the sensor powers up", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:SENS:PMOD 2;:MOVE0 1000000");
    CHECK(activity(h) == (kDelayed | kClosedLoop));
    h.advance_ms(5);
    CHECK((activity(h) & kMoving) != 0);
    h.advance_ms(10);
    CHECK(h.number(":CHAN0:POS?") == 1'000'000);
}

TEST_CASE("MCS2 calibration: a few seconds with ACTIVELY_MOVING and CALIBRATING, then IS_CALIBRATED",
          "[device][mcs2]")
{
    auto config = mcs2_device_config();
    rigsim::mcs2::config_of(config).channels[0].start_position = 3'000'000'000;   // away from the mark
    Mcs2Harness h(config);
    h.send(":CHAN0:CAL:OPT 0;:CAL0");
    CHECK(state(h) == 37 + (1 << 18));   // the guide's example: moving, calibrating, sensor present (6.3.7)
    h.advance_ms(2'999);
    CHECK((state(h) & kCalibrating) != 0);
    h.advance_ms(2);
    CHECK((state(h) & (kCalibrating | kCalibrated)) == kCalibrated);
    h.send(":CHAN0:CAL:OPT 4;:CAL0");   // advanced sensor correction: no feature permission here
    CHECK(h.ask(":CHAN0:ERR?") == "35");
}

TEST_CASE("MCS2 referencing a single mark: forward past it and back, or backward via the end stop", "[device][mcs2]")
{
    auto config = mcs2_device_config();
    for (auto& c : rigsim::mcs2::config_of(config).channels)
        c.start_position = -2'000'000'000;
    Mcs2Harness h(config);
    CHECK(h.number(":CHAN0:POS?") == 0);   // incremental from power-up (2.7)
    h.send(":CHAN0:LSC:OFF 500000000;:REF0");
    CHECK(activity(h) == (kMoving | kClosedLoop | kReferencing));
    h.advance_ms(215);
    CHECK(activity(h) == 0);
    CHECK((state(h) & (kReferenced | kMark)) == (kReferenced | kMark));
    CHECK(h.number(":CHAN0:POS?") == 500'000'000);   // the mark reads the scale offset (2.7.5)
    CHECK(h.number(":CHAN0:REF:DTRM?") == 2'000'000'000);
    // Auto zero, backward start: to the end stop at -10.5 mm, back past the mark, and to it.
    h.send(":CHAN1:REF:OPT 5;:REF1");
    h.advance_ms(1'000);
    CHECK((state(h, 1) & kReferencing) != 0);
    h.advance_ms(920);
    CHECK(activity(h, 1) == 0);
    CHECK(h.number(":CHAN1:POS?") == 0);
    // Abort on end stop: no mark that way: the end stop, and an error.
    h.send(":CHAN2:REF:OPT 9;:REF2");
    h.advance_ms(900);
    CHECK(activity(h, 2) == 0);
    CHECK((state(h, 2) & (kReferenced | kEndStop)) == kEndStop);
    CHECK(h.ask(":CHAN2:ERR?") == "512");
}

TEST_CASE("MCS2 distance-coded marks: two adjacent marks tell the position", "[device][mcs2]")
{
    auto config = mcs2_device_config(1);
    auto& c = rigsim::mcs2::config_of(config).channels[0];
    c.positioner_type = 303;
    c.start_position = 500'000'000;
    c.calibration_ms = 0;
    Mcs2Harness h(config);
    // Calibration with Detect Distance Code Inversion (option bit 1) finds the marks not inverted.
    h.send(":CHAN0:REF:DCIN 1;:CHAN0:CAL:OPT 2;:CAL0");
    h.advance_ms(1);
    CHECK(h.ask(":CHAN0:REF:DCIN?") == "0");
    h.send(":CHAN0:CAL:OPT 0");
    h.send(":REF0");
    h.advance_ms(1'000);
    CHECK(activity(h) == 0);
    CHECK((state(h) & kReferenced) != 0);
    CHECK(h.number(":CHAN0:POS?") == 4'000'000'000);   // the second mark forward, 2 mm apart
    CHECK(h.number(":CHAN0:REF:DTRM?") == 3'500'000'000);
}

TEST_CASE("MCS2 end-stop types: a new type must be calibrated, then the reference is at the safe end stop",
          "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:PTYP 342");
    CHECK((state(h) & (kCalibrated | kReferenced)) == 0);   // cleared by a new type (4.4.6)
    CHECK(h.ask(":CHAN0:PTYP:NAME?") == "\"SL...S1LE\"");
    h.send(":REF0");
    CHECK(h.ask(":CHAN0:ERR?") == "273");   // NOT_CALIBRATED
    h.send(":CAL0");
    h.advance_ms(3'001);
    CHECK(h.number(":CHAN0:POS?") == 10'500'000'000);   // calibrated at the forward (safe) end stop
    h.send(":REF0");
    h.advance_ms(100);
    CHECK(activity(h) == 0);
    CHECK((state(h) & kReferenced) != 0);
    CHECK(h.number(":CHAN0:POS?") == -50'000'000);   // zero at the end stop, a short way off it
}

TEST_CASE("MCS2 broadcast stop: a channel meeting an end stop stops the others", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:BST:OPT 1;:CHAN1:VEL 1000000000;:MOVE1 5000000000");
    h.send(":MOVE0 20000000000");
    h.advance_ms(1'100);
    CHECK(h.ask(":CHAN0:ERR?") == "512");
    CHECK(activity(h, 1) == 0);
    CHECK(h.ask(":CHAN1:ERR?") == "25");   // the others end ABORTED (2.13)
}

TEST_CASE("MCS2 a connection that goes stops the movements it started, not the others'", "[device][mcs2]")
{
    Mcs2Harness h;
    std::string sink;
    auto other = h.open(sink);
    h.send_to(*other, sink, ":CHAN1:VEL 1000000;:MOVE1 1000000000");
    h.send(":CHAN0:VEL 1000000;:MOVE0 1000000000");
    h.advance_ms(10);
    CHECK((activity(h, 1) & kMoving) != 0);
    other.reset();
    CHECK(activity(h, 1) == 0);
    CHECK(h.ask(":CHAN1:ERR?") == "25");
    CHECK((activity(h, 0) & kMoving) != 0);
}

TEST_CASE("MCS2 command group: its commands wait for CLOSe, queries give their values then", "[device][mcs2]")
{
    Mcs2Harness h;
    std::string sink;
    auto other = h.open(sink);
    h.send(":CGR:OPEN 0");
    h.send(":CHAN0:MMOD 0");
    h.send(":MOVE0 1000000000");
    h.send(":MOVE1 500000000");
    CHECK(h.ask(":CHAN0:POS:TARG?").empty());   // appended, not answered
    CHECK(h.send_to(*other, sink, ":CHAN0:STAT?;:CHAN1:STAT?") == "295008; 295008\r\n");   // another connection: idle
    CHECK(h.ask(":CGR:FIN?") == "0");
    h.send(":CGR:CLOS");
    CHECK(h.ask(":CGR:FIN?") == "1");
    CHECK(h.ask(":CGR:VAL?") == "1000000000");
    CHECK((activity(h, 0) & kMoving) != 0);
    CHECK((activity(h, 1) & kMoving) != 0);
    h.send(":CGR:OPEN 1");   // an external trigger needs the I/O module
    h.send(":CGR:OPEN 0;:CHAN0:PTYP:NAME?;:CGR:ABOR");   // not groupable (column CG)
    CHECK(h.errors() == std::vector<std::string>{"257,\"No IO module present\"", "36,\"Command not groupable\""});
}

TEST_CASE("MCS2 trajectory stream: frames at the base rate, linearly interpolated, channels busy meanwhile",
          "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":STR:BFRE?");
    CHECK(h.errors() == std::vector<std::string>{"768,\"Invalid stream handle\""});
    h.send(":DEV:STR:BAS 100;OPT 0");   // the guide's example (6.5.2)
    h.send(":STR:OPEN 0");
    CHECK(h.ask(":STR:BFRE?") == "1024");
    h.send("STR:FRAM 0,1000000,1,100000");
    h.send("STR:FRAM 0,2000000,1,150000");
    h.send("STR:FRAM 0,3000000,1,200000");
    CHECK(h.ask(":STR:BFRE?") == "1018");   // two positions a frame
    CHECK((state(h, 0) & 0x1000) != 0);     // IS_STREAMING
    h.send(":MOVE0 5;:STOP1");
    CHECK(h.errors() == std::vector<std::string>{"771,\"Busy streaming\"", "771,\"Busy streaming\""});
    CHECK(h.number(":DEV:STAT?") == 0);   // ready, not running: a short stream starts when closed
    h.send(":STR:CLOS");
    CHECK(h.number(":DEV:STAT?") == 0x1000);
    h.advance_ms(5);
    CHECK(h.number(":CHAN0:POS?") == 500'000);   // half way to the first frame
    h.advance_ms(10);
    CHECK(h.number(":CHAN0:POS?") == 1'500'000);
    CHECK(h.number(":CHAN1:POS?") == 125'000);
    h.advance_ms(16);
    CHECK(h.number(":CHAN0:POS?") == 3'000'000);
    CHECK(h.number(":CHAN1:POS?") == 200'000);
    CHECK(h.number(":DEV:STAT?") == 0);
    CHECK((state(h, 0) & (0x1000 | 0x1)) == 0);
    CHECK(h.errors().empty());
}

TEST_CASE("MCS2 trajectory stream: starts half full, underflows if not closed, and is bounded", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":STR:OPEN 0");
    for (int k = 1; k <= 511; ++k)
        h.send(":STR:FRAM 0," + std::to_string(k * 1000));
    CHECK(h.number(":DEV:STAT?") == 0);
    h.send(":STR:FRAM 0,512000");   // 512 of 1024 positions: stream ready, direct mode runs
    CHECK(h.number(":DEV:STAT?") == 0x1000);
    for (int k = 513; k <= 1024; ++k)
        h.send(":STR:FRAM 0," + std::to_string(k * 1000));
    h.send(":STR:FRAM 0,0");   // the frame run at the start has freed one place
    h.send(":STR:FRAM 0,0");
    CHECK(h.errors() == std::vector<std::string>{"13,\"Buffer overflow\""});
    h.advance_ms(1'030);
    CHECK(h.number(":DEV:STAT?") == 0);
    CHECK(h.ask(":CHAN0:ERR?") == "12");   // not closed: a buffer underflow after the last frame
    CHECK((state(h, 0) & 0x1000) == 0);
    h.send(":STR:OPEN 0;:STR:FRAM 0,5;:STR:CLOS");   // one frame is not a stream
    CHECK(h.errors() == std::vector<std::string>{"770,\"Insufficient frames\""});
    h.send(":CHAN0:SENS:PMOD 2;:STR:OPEN 0;:STR:FRAM 0,5");
    CHECK(h.errors() == std::vector<std::string>{"263,\"Invalid sensor mode\""});
    h.send(":STR:ABOR;:STR:OPEN 1");
    CHECK(h.errors() == std::vector<std::string>{"257,\"No IO module present\""});
}

TEST_CASE("MCS2 relative moves accumulate during the power-save delay, and after a braking stop start from "
          "where it stops",
          "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:SENS:PMOD 2;:CHAN0:MMOD 1;VEL 10000000000");
    h.send(":MOVE0 1000000000");
    CHECK(h.number(":CHAN0:POS:TARG?") == 1'000'000'000);   // known at the command
    h.send(":MOVE0 1000000000");
    h.advance_ms(1'000);
    CHECK(h.number(":CHAN0:POS?") == 2'000'000'000);
    // Braking: 1 mm/s², a stop at 1 mm/s leaves 0.5 mm to go; a relative move then adds to where
    // the braking ends, not to the stopped move's target.
    h.send(":CHAN0:SENS:PMOD 1;:CHAN0:VEL 1000000000;ACC 1000000000;:MOVE0 5000000000");
    h.advance_ms(1'000);
    h.send(":STOP0");
    CHECK(h.number(":CHAN0:POS:TARG?") == 3'000'000'000);   // 2 + 0.5 accelerating + 0.5 braking
    h.send(":MOVE0 1000000");
    CHECK(h.number(":CHAN0:POS:TARG?") == 3'001'000'000);
}

TEST_CASE("MCS2 braking never passes the move's target or an end stop, whatever :ACC became meanwhile",
          "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":CHAN0:VEL 10000000000;ACC 100000000000000");   // 10 mm/s, 100 m/s²
    h.send(":MOVE0 10400000000");                           // 10.4 mm, 0.1 mm before the end stop
    h.advance_ms(1'000);
    h.send(":CHAN0:ACC 1000000");                           // 1 µm/s²: a stop would take 50 m
    h.send(":STOP0");
    h.advance_ms(100);
    CHECK(activity(h) == 0);
    CHECK(h.number(":CHAN0:POS?") <= 10'400'000'000);
    CHECK(h.ask(":CHAN0:ERR?") == "25");
}

TEST_CASE("MCS2 referencing: the range limit is an end stop, and an aborted search leaves the scale as it was",
          "[device][mcs2]")
{
    auto config = mcs2_device_config();
    for (auto& c : rigsim::mcs2::config_of(config).channels)
        c.start_position = 2'000'000'000;
    Mcs2Harness h(config);
    // The mark (physical 0) is 2 mm behind; with the limit 1 mm either side, the search forwards
    // turns at +1 mm and meets the other limit before the mark: not found (2.12).
    h.send(":CHAN0:RLIM:MIN -1000000000;MAX 1000000000;:CHAN0:REF:OPT 0;:REF0");
    h.advance_ms(1'000);
    CHECK(activity(h) == 0);
    CHECK((state(h) & kReferenced) == 0);
    CHECK(h.ask(":CHAN0:ERR?") == "512");
    CHECK(h.number(":CHAN0:POS?") == -1'000'000'000);
    // Auto zero is committed when the search ends: stopped before, the offset stays.
    h.send(":CHAN1:LSC:OFF 7000000000;:CHAN1:REF:OPT 5;:REF1");
    h.advance_ms(50);
    h.send(":STOP1");
    CHECK(h.ask(":CHAN1:LSC:OFF?;:CHAN1:REF:DTRM?") == "7000000000; 0");
    CHECK((state(h, 1) & kReferenced) == 0);
}

TEST_CASE("MCS2 trajectory stream: its channels refuse configuration, and *RST ends it", "[device][mcs2]")
{
    Mcs2Harness h;
    h.send(":STR:OPEN 0;:STR:FRAM 0,1000000;:STR:FRAM 0,2000000");
    h.send(":CHAN0:AMPL 0;:CHAN0:SENS:PMOD 2;:MOD0:PSUP 0");
    CHECK(h.errors() == std::vector<std::string>{"771,\"Busy streaming\"", "771,\"Busy streaming\"",
                                                 "771,\"Busy streaming\""});
    CHECK(h.ask(":CHAN0:AMPL?") == "1");
    h.send("*RST");
    std::string sink;
    auto again = h.open(sink);
    CHECK(h.send_to(*again, sink, ":CHAN0:STAT?") == "295008\r\n");   // no IS_STREAMING
    h.send_to(*again, sink, ":MOVE0 1000");
    CHECK(h.send_to(*again, sink, ":SYST:ERR:COUN?") == "0\r\n");
}
