// The device faults of the control API, parsed once (emulator/core/control_surface.hpp).
#include "emulator/core/control_surface.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

namespace test_device_fault {

using namespace rigsim;
using nlohmann::json;

TEST_CASE("parse_device_fault: every kind by its name, with its parameters typed", "[unit][control][faults]")
{
    for (const auto kind : kFaultKinds) {
        DeviceFault f;
        const json params = kind == FaultKind::LimitSwitch ? json{{"side", "reverse"}} : json::object();
        REQUIRE_FALSE(parse_device_fault(fault_name(kind), params, f));
        CHECK(f.kind == kind);
    }
    DeviceFault slip;
    REQUIRE_FALSE(parse_device_fault("slip", json{{"counts", 2560}, {"fraction", 0.25}}, slip));
    CHECK(slip.slip_counts == std::optional<double>(2560));
    CHECK(slip.slip_fraction == std::optional<double>(0.25));
    DeviceFault bare;
    REQUIRE_FALSE(parse_device_fault("slip", json::object(), bare));
    CHECK_FALSE(bare.slip_counts);   // each family says what a slip without figures means
    CHECK_FALSE(bare.slip_fraction);
    DeviceFault side;
    REQUIRE_FALSE(parse_device_fault("limit_switch", json{{"side", "forward"}}, side));
    CHECK(side.limit_side == 1);
}

TEST_CASE("parse_device_fault: what is wrong is a 400 naming the field", "[unit][control][faults]")
{
    DeviceFault f;
    const auto message = [&](std::string_view kind, const json& params) {
        const auto r = parse_device_fault(kind, params, f);
        REQUIRE(r);
        CHECK(r->status == 400);
        return r->message;
    };
    CHECK(message("melt", json::object())
          == "\"kind\": \"melt\" is no device fault (stall, slip, sensor_failure, reference_lost, limit_switch)");
    CHECK(message("stall", json{{"force", 3}}) == "\"force\": not a parameter of a stall fault (it takes none)");
    CHECK(message("slip", json{{"side", "forward"}})
          == "\"side\": not a parameter of a slip fault (it takes counts, fraction)");
    CHECK(message("slip", json{{"fraction", 1.5}}) == "\"fraction\": expected a number from 0 to 1, got 1.5");
    CHECK(message("slip", json{{"counts", -1}}) == "\"counts\": expected a number >= 0, got -1");
    CHECK(message("slip", json{{"counts", "many"}}) == "\"counts\": expected a number >= 0, got \"many\"");
    CHECK(message("limit_switch", json::object()) == "\"side\": \"forward\" or \"reverse\" is required");
    CHECK(message("limit_switch", json{{"side", "up"}})
          == "\"side\": \"forward\" or \"reverse\" is required, got \"up\"");
}

} // namespace test_device_fault
