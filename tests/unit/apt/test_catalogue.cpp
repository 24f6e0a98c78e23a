// The catalogue's models keep their values: a few controllers and shipped stages (config/stages)
// pinned field by field.
#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/shipped_stages.hpp"
#include "emulator/apt/messages.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

namespace test_catalogue {

using namespace rigsim::apt;

TEST_CASE("catalogue: TDC001 and KST101 keep their identity and scaling", "[unit][apt][catalogue]")
{
    const auto* tdc = find_controller("TDC001");
    REQUIRE(tdc);
    CHECK(tdc->serial_prefix == 83);
    CHECK(tdc->hw_type == 31);
    CHECK(tdc->motor == MotorKind::DcServo);
    CHECK(tdc->notes == "APT DC Motor Controller");
    // Thorlabs' scaling: T = 2048 / 6 MHz; velocity × T × 65536, acceleration × T² × 65536.
    const double t = 2048.0 / 6e6;
    CHECK(tdc->velocity_per_count_s == t * 65536.0);
    CHECK(tdc->acceleration_per_count_s2 == t * t * 65536.0);
    CHECK_FALSE(tdc->rack);
    CHECK(tdc->max_bays == 1);
    CHECK(tdc->jerk_per_count_s3 == 0);
    CHECK_FALSE(tdc->rich_fault_reports);

    const auto* kst = find_controller("KST101");
    REQUIRE(kst);
    CHECK(kst->serial_prefix == 26);
    CHECK(kst->motor == MotorKind::Stepper);
    CHECK(kst->notes == "Stepper Motor Controller");
    CHECK(kst->velocity_per_count_s == 1.0);
    CHECK(kst->acceleration_per_count_s2 == 1.0);
    CHECK(kst->rich_fault_reports);
}

TEST_CASE("catalogue: BBD203 is a three-bay brushless rack with PMD jerk scaling", "[unit][apt][catalogue]")
{
    const auto* bbd = find_controller("BBD203");
    REQUIRE(bbd);
    CHECK(bbd->serial_prefix == 73);
    CHECK(bbd->hw_type == 45);
    CHECK(bbd->motor == MotorKind::Brushless);
    CHECK(bbd->notes == "Brushless DC Motor Controller");
    CHECK(bbd->velocity_per_count_s == 134'218.0 / 20'000.0);
    CHECK(bbd->acceleration_per_count_s2 == 13.7439 / 20'000.0);
    CHECK(bbd->rack);
    CHECK(bbd->max_bays == 3);
    CHECK(bbd->bay_hw_type == 44);
    CHECK(bbd->bay_serial_prefix == 94);
    CHECK(bbd->jerk_per_count_s3 == 92.2337 / 20'000.0);
    CHECK_FALSE(bbd->rich_fault_reports);

    const auto* bsc = find_controller("BSC203");
    REQUIRE(bsc);
    CHECK(bsc->serial_prefix == 70);
    CHECK(bsc->bay_hw_type == 45);
    CHECK(bsc->bay_serial_prefix == 70);
    CHECK(bsc->jerk_per_count_s3 == 0);
}

TEST_CASE("catalogue: MTS50-Z8, DRV014, PRM1-Z8 and MLS203-Y keep their values", "[unit][apt][catalogue]")
{
    const auto* mts = find_stage("MTS50-Z8");
    REQUIRE(mts);
    CHECK(mts->motor == MotorKind::DcServo);
    CHECK(mts->travel_mm == 50.0);
    CHECK(mts->counts_per_mm == 34'304.0);
    CHECK(mts->max_velocity_mm_s == 2.4);
    CHECK(mts->acceleration_mm_s2 == 1.5);
    CHECK(mts->home_velocity_mm_s == 1.0);
    CHECK(mts->home_offset_mm == 0.3);
    CHECK(mts->kind == StageKind::Linear);
    CHECK(mts->pmd_part_number.empty());

    const auto* drv = find_stage("DRV014");
    REQUIRE(drv);
    CHECK(drv->motor == MotorKind::Stepper);
    CHECK(drv->travel_mm == 50.0);
    CHECK(drv->counts_per_mm == 25'600.0);
    CHECK(drv->max_velocity_mm_s == 2.0);
    CHECK(drv->acceleration_mm_s2 == 4.0);
    CHECK(drv->home_offset_mm == 0.5);

    const auto* prm = find_stage("PRM1-Z8");
    REQUIRE(prm);
    CHECK(prm->travel_mm == 0.0);   // endless
    CHECK(prm->counts_per_mm == 1'919.6418);
    CHECK(prm->home_velocity_mm_s == 10.0);
    CHECK(prm->home_offset_mm == 4.0);
    CHECK(prm->kind == StageKind::Rotary);

    const auto* mls = find_stage("MLS203-Y");
    REQUIRE(mls);
    CHECK(mls->motor == MotorKind::Brushless);
    CHECK(mls->travel_mm == 75.0);
    CHECK(mls->counts_per_mm == 20'000.0);
    CHECK(mls->max_velocity_mm_s == 100.0);
    CHECK(mls->acceleration_mm_s2 == 500.0);
    CHECK(mls->home_velocity_mm_s == 10.0);
    CHECK(mls->home_offset_mm == 1.0);
    CHECK(mls->velocity_per_mm_s == 134'218.0);
    CHECK(mls->acceleration_per_mm_s2 == 13.7439);
    CHECK(mls->pmd_stage_id == 0x11);
    CHECK(mls->pmd_part_number == "MLS203 Y Axis");
    CHECK(mls->pmd_max_velocity == 26'843'546);
    CHECK(mls->pmd_max_acceleration == 27'488);
}

TEST_CASE("catalogue: every model the messages list is found, and nothing else", "[unit][apt][catalogue]")
{
    for (const char* name : {"TDC001", "KDC101", "TST001", "KST101", "BSC203", "BBD203", "TSC001", "KSC101", "TPZ001",
                             "KPZ101", "BPC301", "BPC303", "TSG001", "KSG101"})
        CHECK(find_controller(name));
    for (const char* name : {"DRV001", "ZST225B", "DRV014", "MTS50-Z8", "MTS25-Z8", "Z825B", "Z812B", "PRM1-Z8",
                             "MLS203-X", "MLS203-Y", "DDSM100"})
        CHECK(find_stage(name));
    CHECK_FALSE(find_controller("TDC002"));
    CHECK_FALSE(find_stage("MTS99"));
}

namespace {

using Ids = std::set<std::uint16_t>;

// The manual's "Message Cross Reference by Unit Part Number" tables as printed (p. 132-138),
// IDs read as the errata say ("0x002H" = 0x0002, "0x005H" = 0x0005, "0x006H" = 0x0006).
const Ids kXrefTsc001{0x0223, 0x0210, 0x0211, 0x0212, 0x0080, 0x0011, 0x0012, 0x0005, 0x0006, 0x0065, 0x0066,
                      0x0464, 0x0453, 0x0465, 0x04B3, 0x04B4, 0x04B5, 0x04B6, 0x04B7, 0x04B8, 0x04B9, 0x0481,
                      0x04C0, 0x04C1, 0x04C2, 0x04C3, 0x04C4, 0x04C5, 0x04C6, 0x04C7, 0x04C8, 0x04CB, 0x04CC, 0x04CD};
const Ids kXrefTpz001{0x0223, 0x0210, 0x0211, 0x0212, 0x0002, 0x0080, 0x0011, 0x0012, 0x0005, 0x0006,
                      0x0640, 0x0641, 0x0642, 0x0643, 0x0644, 0x0645, 0x0646, 0x0647, 0x0648, 0x0652, 0x0653, 0x0654,
                      0x0655, 0x0656, 0x0657, 0x0661, 0x0700, 0x0701, 0x0702, 0x0703, 0x0704, 0x0705, 0x0706, 0x0707,
                      0x07D0, 0x07D1, 0x07D2, 0x07D3, 0x07D4, 0x07D5, 0x07D6};
const Ids kXrefBpc30x{0x0223, 0x0210, 0x0211, 0x0212, 0x0002, 0x0080, 0x0011, 0x0012, 0x0005, 0x0006, 0x0060,
                      0x0061, 0x0226, 0x0227, 0x0228, 0x0229, 0x0230, 0x0640, 0x0641, 0x0642, 0x0643, 0x0644, 0x0645,
                      0x0646, 0x0647, 0x0648, 0x0652, 0x0653, 0x0654, 0x0655, 0x0656, 0x0657, 0x065B, 0x065C, 0x0661,
                      0x0662, 0x0700, 0x0701, 0x0702, 0x0703, 0x0704, 0x0705, 0x0706, 0x0707, 0x0658, 0x0680, 0x0681,
                      0x0682, 0x0683, 0x0684, 0x0685, 0x0686};
const Ids kXrefTsg001{0x0223, 0x0210, 0x0211, 0x0212, 0x0002, 0x0080, 0x0011, 0x0012, 0x0005, 0x0006, 0x0065,
                      0x0066, 0x0661, 0x0662, 0x07D0, 0x07D1, 0x07D2, 0x07D3, 0x0658, 0x0650, 0x0651, 0x07DA, 0x07DB,
                      0x07DC, 0x07DD, 0x07DE};

/// A model's own messages as a set.
Ids takes_of(const ControllerModel& c)
{
    return Ids(c.takes.ids, c.takes.ids + c.takes.count);
}

/// A cross-reference table without the generic messages (MOD_, HW_, RACK_, HUB_), which the
/// shell handles for every unit, minus `removed`, plus `added`.
Ids expected_from(const Ids& xref, const Ids& removed, const Ids& added)
{
    Ids out;
    for (const auto id : xref) {
        const auto* m = find_message(id);
        REQUIRE(m);
        if (m->group != Group::Generic && !removed.count(id))
            out.insert(id);
    }
    out.insert(added.begin(), added.end());
    return out;
}

struct UnitRow {
    std::string_view name;
    UnitKind kind;
    std::uint32_t serial_prefix;
    std::string_view notes;
    bool rich_fault_reports;
};

} // namespace

TEST_CASE("catalogue: each new unit's message set is its cross-reference table with the documented choices",
          "[unit][apt][catalogue]")
{
    // TSC001/KSC101 (p. 138): MOVE_COMPLETED, MOVE_ABSOLUTE and MOVE_STOP have no solenoid
    // meaning (D-4); the host acknowledges the status updates with MOT_ACK_DCSTATUSUPDATE (D-3).
    const auto solenoid = expected_from(kXrefTsc001,
                                        {MGMSG_MOT_MOVE_COMPLETED, MGMSG_MOT_MOVE_ABSOLUTE, MGMSG_MOT_MOVE_STOP},
                                        {MGMSG_MOT_ACK_DCSTATUSUPDATE});
    // TPZ001/KPZ101 (p. 133) + D-5: PZSTATUSBITS (p. 101), ACK_PZSTATUSUPDATE (p. 105),
    // TPZ_SLEWRATES (p. 123).
    const auto tpz = expected_from(kXrefTpz001, {},
                                   {MGMSG_PZ_REQ_PZSTATUSBITS, MGMSG_PZ_GET_PZSTATUSBITS, MGMSG_PZ_ACK_PZSTATUSUPDATE,
                                    MGMSG_PZ_SET_TPZ_SLEWRATES, MGMSG_PZ_REQ_TPZ_SLEWRATES, MGMSG_PZ_GET_TPZ_SLEWRATES});
    // BPC30x (p. 132) + D-6: MAXTRAVEL (p. 118's example addresses bay 0x22).
    const auto bpc = expected_from(kXrefBpc30x, {}, {MGMSG_PZ_REQ_MAXTRAVEL, MGMSG_PZ_GET_MAXTRAVEL});
    // TSG001/KSG101 (p. 134): as printed.
    const auto tsg = expected_from(kXrefTsg001, {}, {});

    CHECK(solenoid.size() == 21);
    CHECK(tpz.size() == 37);
    CHECK(bpc.size() == 37);
    CHECK(tsg.size() == 14);
    for (const char* name : {"TSC001", "KSC101"})
        CHECK(takes_of(*find_controller(name)) == solenoid);
    for (const char* name : {"TPZ001", "KPZ101"})
        CHECK(takes_of(*find_controller(name)) == tpz);
    for (const char* name : {"BPC301", "BPC303"})
        CHECK(takes_of(*find_controller(name)) == bpc);
    for (const char* name : {"TSG001", "KSG101"})
        CHECK(takes_of(*find_controller(name)) == tsg);
    // Listed once each; the motor controllers keep the empty set (their modules decide).
    for (const char* name : {"TSC001", "TPZ001", "BPC303", "TSG001"})
        CHECK(find_controller(name)->takes.count == takes_of(*find_controller(name)).size());
    for (const char* name : {"TDC001", "KDC101", "TST001", "KST101", "BSC203", "BBD203"})
        CHECK(find_controller(name)->takes.empty());
    // Outside the sets: LUTVALUETYPE and IOSETTINGS (MPZ601 only, p. 135); SET_ZERO on a TPZ001.
    CHECK_FALSE(find_controller("BPC303")->takes.contains(MGMSG_PZ_SET_LUTVALUETYPE));
    CHECK_FALSE(find_controller("TPZ001")->takes.contains(MGMSG_PZ_SET_IOSETTINGS));
    CHECK_FALSE(find_controller("TPZ001")->takes.contains(MGMSG_PZ_SET_ZERO));
}

TEST_CASE("catalogue: what the K-Cubes and T-Cubes of the later generation take beyond their lists, pinned",
          "[unit][apt][catalogue]")
{
    const Ids ksc{MGMSG_MOT_REQ_STATUSBITS, MGMSG_MOT_GET_STATUSBITS, MGMSG_MOT_REQ_STATUSUPDATE,
                  MGMSG_MOT_SET_KCUBEMMIPARAMS, MGMSG_MOT_REQ_KCUBEMMIPARAMS, MGMSG_MOT_GET_KCUBEMMIPARAMS,
                  MGMSG_MOT_SET_KCUBETRIGIOCONFIG, MGMSG_MOT_REQ_KCUBETRIGIOCONFIG, MGMSG_MOT_GET_KCUBETRIGIOCONFIG};
    const Ids kpz{0x0660, 0x07F0, 0x07F1, 0x07F2, 0x07F3, 0x07F4, 0x07F5};
    const Ids ksg{0x0660, 0x07F6, 0x07F7, 0x07F8, 0x07F9, 0x07FA, 0x07FB};
    const Ids tcube{MGMSG_PZ_REQ_PZSTATUSUPDATE};
    // The issue-3 entries carry the same lists: the module takes them only with the later generation.
    for (const auto firmware : {Firmware::Issue3, Firmware::Issue44_1}) {
        auto later_of = [firmware](std::string_view name) {
            const auto& s = find_controller(name, firmware)->later_takes;
            return Ids(s.ids, s.ids + s.count);
        };
        CHECK(later_of("KSC101") == ksc);
        CHECK(later_of("KPZ101") == kpz);
        CHECK(later_of("KSG101") == ksg);
        CHECK(later_of("TPZ001") == tcube);
        CHECK(later_of("TSG001") == tcube);
        for (const char* name : {"TDC001", "KDC101", "KST101", "BBD203", "TSC001", "BPC301", "BPC303"})
            CHECK(find_controller(name, firmware)->later_takes.empty());
        // The K-Cubes take their T-Cube's list.
        const std::pair<const char*, const char*> kcubes[]{{"KSC101", "TSC001"}, {"KPZ101", "TPZ001"},
                                                            {"KSG101", "TSG001"}};
        for (const auto& [kcube, tcube_name] : kcubes)
            CHECK(takes_of(*find_controller(kcube, firmware)) == takes_of(*find_controller(tcube_name, firmware)));
    }
}

TEST_CASE("catalogue: the solenoid, piezo and strain gauge units' identity, ACK and LUT figures",
          "[unit][apt][catalogue]")
{
    // Prefixes: Thorlabs' own (D-1; the manual lists none for these units).
    const UnitRow rows[]{
        {"TSC001", UnitKind::Solenoid, 85, "APT Solenoid Controller", false},
        {"KSC101", UnitKind::Solenoid, 68, "Solenoid Controller", true},
        {"TPZ001", UnitKind::Piezo, 81, "APT Piezo Driver", false},
        {"KPZ101", UnitKind::Piezo, 29, "Piezo Controller", true},
        {"BPC301", UnitKind::Piezo, 41, "Piezo Controller", false},
        {"BPC303", UnitKind::Piezo, 71, "Piezo Controller", false},
        {"TSG001", UnitKind::StrainGauge, 84, "APT Strain Gauge Reader", false},
        {"KSG101", UnitKind::StrainGauge, 59, "Strain Gauge Reader", true},
    };
    for (const auto& row : rows) {
        INFO(row.name);
        const auto* c = find_controller(row.name);
        REQUIRE(c);
        CHECK(c->kind == row.kind);
        CHECK(c->serial_prefix == row.serial_prefix);
        CHECK(c->notes == row.notes);
        CHECK(c->rich_fault_reports == row.rich_fault_reports);
        const bool bpc = row.name.substr(0, 3) == "BPC";
        CHECK(c->rack == bpc);
        CHECK(c->hw_type == (bpc ? 45 : 31));
        // Piezo and gauge units are acknowledged with PZ_ACK_PZSTATUSUPDATE (p. 105).
        CHECK(c->ack_id == (row.kind == UnitKind::Solenoid ? MGMSG_MOT_ACK_DCSTATUSUPDATE : MGMSG_PZ_ACK_PZSTATUSUPDATE));
        if (row.kind != UnitKind::Piezo) {
            CHECK(c->lut_max_index == 0);
            CHECK(c->loop_rate_hz == 0);
        }
    }
    // LUT (p. 106, 109): TPZ 0..512 at 250 µs, BPC 0..7999 at 1 ms; loops at those rates.
    for (const char* name : {"TPZ001", "KPZ101"}) {
        const auto* c = find_controller(name);
        CHECK(c->lut_max_index == 512);
        CHECK(c->lut_base_interval_us == 250);
        CHECK(c->loop_rate_hz == 4'000);
    }
    const auto* bpc301 = find_controller("BPC301");
    const auto* bpc303 = find_controller("BPC303");
    CHECK(bpc301->max_bays == 1);
    CHECK(bpc303->max_bays == 3);
    for (const auto* c : {bpc301, bpc303}) {
        CHECK(c->lut_max_index == 7'999);
        CHECK(c->lut_base_interval_us == 1'000);
        CHECK(c->loop_rate_hz == 1'000);
        CHECK(c->bay_hw_type == 45);
        CHECK(c->bay_serial_prefix == c->serial_prefix);
    }
    CHECK(find_controller("TDC001")->ack_id == MGMSG_MOT_ACK_DCSTATUSUPDATE);
    CHECK(find_controller("TDC001")->kind == UnitKind::Motor);
}

} // namespace test_catalogue
