#include "emulator/control/body_state.hpp"

#include <string>

namespace rigsim::control {

namespace {

nlohmann::json faults_json(const models::PhysicalFaults& f)
{
    return {{"stalled", f.stalled},
            {"slip_counts", f.slip_steps},
            {"slip_fraction", f.slip_fraction},
            {"switch_pressed", f.switch_pressed > 0 ? "forward" : f.switch_pressed < 0 ? "reverse" : "none"},
            {"sensor_failed", f.sensor_failed}};
}

void add_body(const models::Body& body, nlohmann::json& ch)
{
    const bool line = body.travel() == models::Travel::Line;
    ch["position_si"] = line ? body.position_m() : body.angle_rad();
    ch["velocity_si"] = line ? body.velocity_m_per_s() : body.angular_velocity_rad_per_s();
    ch["si_unit"] = line ? "m" : "rad";
    ch["body"] = {{"key", body.key()},
                  {"kind", std::string(models::body_kind_name(body.kind()))},
                  {"settling", body.settling()},
                  {"faults", faults_json(body.faults())}};
}

} // namespace

void describe_device(const ControlSurface& surface, const models::World* world, nlohmann::json& out)
{
    surface.describe(out);
    if (!world || !out.contains("channels"))
        return;
    for (auto& ch : out["channels"]) {
        const int index = ch.value("index", -1);
        std::string key;
        if (index < 0 || surface.channel_body_key(static_cast<std::size_t>(index), key))
            continue;
        const models::Body* body = world->find(key);
        if (body && body->travel() != models::Travel::None)
            add_body(*body, ch);
    }
}

} // namespace rigsim::control
