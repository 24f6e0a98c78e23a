// The piezo module's face to the control API: describe (GET), PATCH of TRIG IN and the trace
// query. What a LUT run does on the wire stays in piezo_module.cpp.
#include "emulator/apt/piezo_module.hpp"
#include "emulator/core/log_format.hpp"

#include <nlohmann/json.hpp>


namespace rigsim::apt {

void PiezoModule::describe(nlohmann::json& out) const
{
    const Ticks now = clock_.now();
    const double v = output_at(now);
    out["mode"] = mode_;
    if (unit_.model.takes.contains(MGMSG_PZ_SET_LUTVALUETYPE)) {   // the MPZ601's
        out["lut_value_type"] = lut_value_type_ == 2 ? "position" : "volts";
        out["io_settings"] = {{"amp_current_lim", io_settings_.amp_current_lim},
                              {"amp_lp_filter", io_settings_.amp_lp_filter},
                              {"bnc_trig_or_lv_out", io_settings_.bnc_trig_or_lv_out}};
    }
    out["output_voltage_v"] = v;
    out["output_code"] = code_of(v);
    out["voltage_limit_v"] = max_v_;
    out["position_um"] = actuator_.extension_um();   // the world's actuator, not a protocol word
    out["travel_um"] = actuator_.config().travel_um;
    out["position_code"] = position_word(now);
    out["setpoint_code"] = position_code_;
    // Where the closed loop reads its position: the bay's own stage gauge, or the TPZ/KPZ input
    // (TPZ_IOSETTINGS HubAnalogInput, p. 115) a gauge reader's signal reaches.
    static constexpr const char* kInputs[] = {"hub_a", "hub_b", "sma"};
    if (strain_gauge_)
        out["feedback"] = "stage_gauge";
    else if (fed_back_um(now) && hub_analog_input_ >= 1 && hub_analog_input_ <= 3)
        out["feedback"] = kInputs[hub_analog_input_ - 1];
    else
        out["feedback"] = nullptr;
    out["zeroed"] = zeroed_;
    out["zeroing"] = zero_end_ != kNever;
    out["pi"] = {{"prop", pi_.prop()}, {"int", pi_.integral()}};
    out["slew"] = {{"open", slew_open_}, {"closed", slew_closed_}};
    const auto& p = lut_params_;
    const auto index = lut_.index_at(now);
    const auto value = lut_.value_at(now);
    out["lut"] = {{"loaded", lut_.loaded()},
                  {"capacity", lut_.capacity()},
                  {"params",
                   {{"mode", p.mode}, {"cycle_length", p.cycle_length}, {"num_cycles", p.num_cycles},
                    {"delay_time", p.delay_time}, {"pre_cycle_rest", p.pre_cycle_rest},
                    {"post_cycle_rest", p.post_cycle_rest}, {"op_trig_start", p.op_trig_start},
                    {"op_trig_width", p.op_trig_width}, {"trig_repeat_cycle", p.trig_repeat_cycle}}},
                  {"running", lut_.running_at(now)},
                  {"armed", lut_armed_},
                  {"cycle", lut_.started() ? nlohmann::json(lut_.cycle_at(now)) : nlohmann::json(nullptr)},
                  {"index", index ? nlohmann::json(*index) : nlohmann::json(nullptr)},
                  {"value_code", value ? nlohmann::json(*value) : nlohmann::json(nullptr)}};
    out["trig_in"] = bpc_ ? nlohmann::json(trig_in_) : nlohmann::json(nullptr);
    out["status"] = status_bits();
}

Refused PiezoModule::patch(const nlohmann::json& body)
{
    for (const auto& [key, value] : body.items()) {
        if (key != "trig_in")
            return Refusal{400, "unknown key \"" + key + "\" for a piezo channel (a BPC30x bay takes trig_in)"};
        if (!bpc_)
            return Refusal{400, "\"trig_in\": the " + unit_.model_name + " has no trigger input (the "
                                    "OUTPUTLUTPARAMS trigger modes are not applicable to it, p. 108)"};
        if (!value.is_boolean() && value != "pulse")
            return Refusal{400, "\"trig_in\" is true, false or \"pulse\""};
    }
    if (const auto it = body.find("trig_in"); it != body.end()) {
        const Ticks now = clock_.now();
        check_lut_end(now);
        if (it->is_boolean()) {
            set_trig_in(it->get<bool>(), now);
        } else {   // a pulse: high then low in one tick (as the solenoid's TRIG IN)
            set_trig_in(true, now);
            set_trig_in(false, now);
        }
        record_trace(now);
    }
    return std::nullopt;
}

void PiezoModule::set_trig_in(bool level, Ticks now)
{
    if (level == trig_in_)
        return;
    trig_in_ = level;
    const std::uint16_t mode = lut_.params().mode;
    // p. 108: 0x20 set, the input responds to a rising edge (active high); clear, to a falling one.
    const bool active = level == ((mode & models::LutPlayer::kInputTrigSenseHi) != 0);
    if (!lut_armed_)
        return;
    const bool gated = (mode & models::LutPlayer::kGated) != 0;
    if (active) {
        std::string why;
        if (!start_lut(now, "trig_in", &why))
            log_.warn("control: TRIG IN edge: the armed LUT output does not start: {}", why);
        else if (!gated)
            lut_armed_ = false;   // one START, one triggered run
        return;
    }
    if (gated && lut_live_) {   // 0x40: the trigger is a gate; closed, the output holds where it is
        end_lut(now, "gate_closed");
        lut_.stop(now);
    }
}

Refused PiezoModule::trace(Ticks from, std::size_t max, nlohmann::json& out) const
{
    trace_.to_json(from, max, out);
    return std::nullopt;
}

} // namespace rigsim::apt
