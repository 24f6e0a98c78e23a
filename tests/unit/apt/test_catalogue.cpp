// The catalogue's models keep their values: a few controllers and stages pinned field by field.
#include "emulator/apt/catalogue.hpp"

#include <catch2/catch.hpp>

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
    CHECK_FALSE(mts->rotary);
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
    CHECK(prm->travel_mm == 360.0);
    CHECK(prm->counts_per_mm == 1'919.6418);
    CHECK(prm->home_velocity_mm_s == 10.0);
    CHECK(prm->home_offset_mm == 4.0);
    CHECK(prm->rotary);

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
    for (const char* name : {"TDC001", "KDC101", "TST001", "KST101", "BSC203", "BBD203"})
        CHECK(find_controller(name));
    for (const char* name : {"DRV001", "ZST225B", "DRV014", "MTS50-Z8", "MTS25-Z8", "Z825B", "Z812B", "PRM1-Z8",
                             "MLS203-X", "MLS203-Y", "DDSM100"})
        CHECK(find_stage(name));
    CHECK_FALSE(find_controller("TDC002"));
    CHECK_FALSE(find_stage("MTS99"));
}
