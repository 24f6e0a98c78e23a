#include "emulator/apt/wire_decode.hpp"

#include "emulator/apt/codec.hpp"
#include "emulator/apt/frame_framer.hpp"
#include "emulator/apt/messages.hpp"
#include "emulator/core/device.hpp"
#include "emulator/core/wire_log.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <unordered_map>

namespace rigsim::apt {

namespace {

// The codec structs' member names (codec.hpp, each struct's fields()), by message ID, as one
// space-separated list each: constant data, which compiles in no time, where a table of vectors
// written out as initializer lists took GCC -O3 six seconds. names_table() splits them once; an
// ID given twice would get both lists, which tests/unit/apt/test_apt_wire_decode.cpp (each
// count against the struct's fields) refuses.
struct FieldNames {
    std::uint16_t id;
    std::string_view names;
};
constexpr FieldNames kFieldNames[] = {
    {MGMSG_MOT_SET_POSCOUNTER, "chan_ident position"},
    {MGMSG_MOT_GET_POSCOUNTER, "chan_ident position"},
    {MGMSG_MOT_SET_ENCCOUNTER, "chan_ident encoder_count"},
    {MGMSG_MOT_GET_ENCCOUNTER, "chan_ident encoder_count"},
    {MGMSG_MOT_SET_VELPARAMS, "chan_ident min_velocity acceleration max_velocity"},
    {MGMSG_MOT_GET_VELPARAMS, "chan_ident min_velocity acceleration max_velocity"},
    {MGMSG_MOT_SET_JOGPARAMS, "chan_ident jog_mode jog_step_size jog_min_velocity jog_acceleration jog_max_velocity jog_stop_mode"},
    {MGMSG_MOT_GET_JOGPARAMS, "chan_ident jog_mode jog_step_size jog_min_velocity jog_acceleration jog_max_velocity jog_stop_mode"},
    {MGMSG_MOT_SET_GENMOVEPARAMS, "chan_ident backlash_distance"},
    {MGMSG_MOT_GET_GENMOVEPARAMS, "chan_ident backlash_distance"},
    {MGMSG_MOT_SET_MOVERELPARAMS, "chan_ident relative_distance"},
    {MGMSG_MOT_GET_MOVERELPARAMS, "chan_ident relative_distance"},
    {MGMSG_MOT_SET_MOVEABSPARAMS, "chan_ident absolute_position"},
    {MGMSG_MOT_GET_MOVEABSPARAMS, "chan_ident absolute_position"},
    {MGMSG_MOT_SET_HOMEPARAMS, "chan_ident home_direction limit_switch home_velocity offset_distance"},
    {MGMSG_MOT_GET_HOMEPARAMS, "chan_ident home_direction limit_switch home_velocity offset_distance"},
    {MGMSG_MOT_SET_LIMSWITCHPARAMS, "chan_ident cw_hard_limit ccw_hard_limit cw_soft_limit ccw_soft_limit soft_limit_mode"},
    {MGMSG_MOT_GET_LIMSWITCHPARAMS, "chan_ident cw_hard_limit ccw_hard_limit cw_soft_limit ccw_soft_limit soft_limit_mode"},
    {MGMSG_MOT_SET_DCPIDPARAMS, "chan_ident proportional integral differential integral_limit filter_control"},
    {MGMSG_MOT_GET_DCPIDPARAMS, "chan_ident proportional integral differential integral_limit filter_control"},
    {MGMSG_MOT_SET_AVMODES, "chan_ident mode_bits"},
    {MGMSG_MOT_GET_AVMODES, "chan_ident mode_bits"},
    {MGMSG_MOT_SET_POTPARAMS, "chan_ident zero_wnd vel1 wnd1 vel2 wnd2 vel3 wnd3 vel4"},
    {MGMSG_MOT_GET_POTPARAMS, "chan_ident zero_wnd vel1 wnd1 vel2 wnd2 vel3 wnd3 vel4"},
    {MGMSG_MOT_SET_BUTTONPARAMS, "chan_ident mode position1 position2 time_out_ms not_used"},
    {MGMSG_MOT_GET_BUTTONPARAMS, "chan_ident mode position1 position2 time_out_ms not_used"},
    {MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, "chan_ident kp_pos ki_pos integral_limit kd_pos kd_time_pos kout_pos kvff_pos kaff_pos pos_err_lim not_used1 not_used2"},
    {MGMSG_MOT_GET_PMDPOSITIONLOOPPARAMS, "chan_ident kp_pos ki_pos integral_limit kd_pos kd_time_pos kout_pos kvff_pos kaff_pos pos_err_lim not_used1 not_used2"},
    {MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, "chan_ident cont_current_lim energy_lim motor_lim motor_bias not_used1 not_used2"},
    {MGMSG_MOT_GET_PMDMOTOROUTPUTPARAMS, "chan_ident cont_current_lim energy_lim motor_lim motor_bias not_used1 not_used2"},
    {MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS, "chan_ident time_cycles settle_window track_window not_used1 not_used2"},
    {MGMSG_MOT_GET_PMDTRACKSETTLEPARAMS, "chan_ident time_cycles settle_window track_window not_used1 not_used2"},
    {MGMSG_MOT_SET_PMDPROFILEMODEPARAMS, "chan_ident mode jerk not_used1 not_used2"},
    {MGMSG_MOT_GET_PMDPROFILEMODEPARAMS, "chan_ident mode jerk not_used1 not_used2"},
    {MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, "chan_ident phase kp_current ki_current i_lim_current i_dead_band kff not_used1 not_used2"},
    {MGMSG_MOT_GET_PMDCURRENTLOOPPARAMS, "chan_ident phase kp_current ki_current i_lim_current i_dead_band kff not_used1 not_used2"},
    {MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, "chan_ident phase kp_settled ki_settled i_lim_settled i_dead_band_settled kff_settled not_used1 not_used2"},
    {MGMSG_MOT_GET_PMDSETTLEDCURRENTLOOPPARAMS, "chan_ident phase kp_settled ki_settled i_lim_settled i_dead_band_settled kff_settled not_used1 not_used2"},
    {MGMSG_MOT_SET_PMDSTAGEAXISPARAMS, "chan_ident stage_id axis_id part_no_axis serial_num cnts_per_unit min_pos max_pos max_accn max_dec max_vel reserved"},
    {MGMSG_MOT_GET_PMDSTAGEAXISPARAMS, "chan_ident stage_id axis_id part_no_axis serial_num cnts_per_unit min_pos max_pos max_accn max_dec max_vel reserved"},
    {MGMSG_MOT_SET_POWERPARAMS, "chan_ident rest_factor move_factor"},
    {MGMSG_MOT_GET_POWERPARAMS, "chan_ident rest_factor move_factor"},
    {MGMSG_MOT_SET_TSTACTUATORTYPE, "actuator_ident unused"},
    {MGMSG_MOT_SET_TRIGGER, "chan_ident mode"},
    {MGMSG_MOT_GET_TRIGGER, "chan_ident mode"},
    {MGMSG_MOT_SET_KCUBEMMIPARAMS, "chan_ident js_mode js_max_vel js_accn dir_sense preset_pos1 preset_pos2 disp_brightness disp_timeout disp_dim_level preset_pos3 js_sensitivity reserved"},
    {MGMSG_MOT_GET_KCUBEMMIPARAMS, "chan_ident js_mode js_max_vel js_accn dir_sense preset_pos1 preset_pos2 disp_brightness disp_timeout disp_dim_level preset_pos3 js_sensitivity reserved"},
    {MGMSG_MOT_SET_KCUBETRIGIOCONFIG, "chan_ident trig1_mode trig1_polarity trig2_mode trig2_polarity reserved"},
    {MGMSG_MOT_GET_KCUBETRIGIOCONFIG, "chan_ident trig1_mode trig1_polarity trig2_mode trig2_polarity reserved"},
    {MGMSG_MOT_SET_KCUBEPOSTRIGPARAMS, "chan_ident start_pos_fwd interval_fwd num_pulses_fwd start_pos_rev interval_rev num_pulses_rev pulse_width num_cycles reserved"},
    {MGMSG_MOT_GET_KCUBEPOSTRIGPARAMS, "chan_ident start_pos_fwd interval_fwd num_pulses_fwd start_pos_rev interval_rev num_pulses_rev pulse_width num_cycles reserved"},
    {MGMSG_MOT_SET_KCUBEKSTLOOPPARAMS, "chan_ident loop_mode prop integral diff pid_clip pid_tol encoder_const"},
    {MGMSG_MOT_GET_KCUBEKSTLOOPPARAMS, "chan_ident loop_mode prop integral diff pid_clip pid_tol encoder_const"},
    {MGMSG_MOD_SET_CHANENABLESTATE, "chan_ident enable_state"},
    {MGMSG_MOD_GET_CHANENABLESTATE, "chan_ident enable_state"},
    {MGMSG_HW_RICHRESPONSE, "msg_ident code notes"},
    {MGMSG_HW_START_UPDATEMSGS, "update_rate"},
    {MGMSG_HW_GET_INFO, "serial_number model_number type firmware_version notes nchs"},
    {MGMSG_RACK_REQ_BAYUSED, "bay_ident"},
    {MGMSG_RACK_GET_BAYUSED, "bay_ident bay_state"},
    {MGMSG_HUB_GET_BAYUSED, "bay_ident"},
    {MGMSG_RACK_GET_STATUSBITS, "status_bits"},
    {MGMSG_RACK_SET_DIGOUTPUTS, "dig_outputs bay_ident"},
    {MGMSG_RACK_REQ_DIGOUTPUTS, "dig_outputs bay_ident"},
    {MGMSG_RACK_GET_DIGOUTPUTS, "dig_outputs bay_ident"},
    {MGMSG_MOT_MOVE_RELATIVE, "chan_ident relative_distance"},
    {MGMSG_MOT_MOVE_ABSOLUTE, "chan_ident absolute_distance"},
    {MGMSG_MOT_MOVE_JOG, "chan_ident direction"},
    {MGMSG_MOT_MOVE_VELOCITY, "chan_ident direction"},
    {MGMSG_MOT_MOVE_STOP, "chan_ident stop_mode"},
    {MGMSG_MOT_SET_EEPROMPARAMS, "chan_ident msg_id"},
    {MGMSG_MOT_GET_STATUSBITS, "chan_ident status_bits"},
    {MGMSG_MOT_SET_SOL_OPERATINGMODE, "chan_ident operating_mode"},
    {MGMSG_MOT_GET_SOL_OPERATINGMODE, "chan_ident operating_mode"},
    {MGMSG_MOT_SET_SOL_CYCLEPARAMS, "chan_ident on_time_250us off_time_250us num_cycles"},
    {MGMSG_MOT_GET_SOL_CYCLEPARAMS, "chan_ident on_time_250us off_time_250us num_cycles"},
    {MGMSG_MOT_SET_SOL_INTERLOCKMODE, "chan_ident interlock_mode"},
    {MGMSG_MOT_GET_SOL_INTERLOCKMODE, "chan_ident interlock_mode"},
    {MGMSG_MOT_SET_SOL_STATE, "chan_ident state"},
    {MGMSG_MOT_GET_SOL_STATE, "chan_ident state"},
    {MGMSG_PZ_SET_OUTPUTVOLTS, "chan_ident voltage"},
    {MGMSG_PZ_GET_OUTPUTVOLTS, "chan_ident voltage"},
    {MGMSG_PZ_SET_OUTPUTPOS, "chan_ident position_sw"},
    {MGMSG_PZ_GET_OUTPUTPOS, "chan_ident position_sw"},
    {MGMSG_PZ_SET_INPUTVOLTSSRC, "chan_ident volt_src"},
    {MGMSG_PZ_GET_INPUTVOLTSSRC, "chan_ident volt_src"},
    {MGMSG_PZ_SET_PICONSTS, "chan_ident prop_const int_const"},
    {MGMSG_PZ_GET_PICONSTS, "chan_ident prop_const int_const"},
    {MGMSG_PZ_SET_OUTPUTLUT, "chan_ident index output"},
    {MGMSG_PZ_GET_OUTPUTLUT, "chan_ident index output"},
    {MGMSG_PZ_SET_OUTPUTLUTPARAMS, "chan_ident mode cycle_length num_cycles delay_time pre_cycle_rest post_cycle_rest op_trig_start op_trig_width trig_repeat_cycle"},
    {MGMSG_PZ_GET_OUTPUTLUTPARAMS, "chan_ident mode cycle_length num_cycles delay_time pre_cycle_rest post_cycle_rest op_trig_start op_trig_width trig_repeat_cycle"},
    {MGMSG_PZ_SET_TPZ_DISPSETTINGS, "disp_intensity"},
    {MGMSG_PZ_GET_TPZ_DISPSETTINGS, "disp_intensity"},
    {MGMSG_PZ_SET_TPZ_IOSETTINGS, "chan_ident voltage_limit hub_analog_input future_use1 future_use2"},
    {MGMSG_PZ_GET_TPZ_IOSETTINGS, "chan_ident voltage_limit hub_analog_input future_use1 future_use2"},
    {MGMSG_PZ_SET_IOSETTINGS, "chan_ident amp_current_lim amp_lp_filter feedback_sig bnc_trig_or_lv_out"},
    {MGMSG_PZ_GET_IOSETTINGS, "chan_ident amp_current_lim amp_lp_filter feedback_sig bnc_trig_or_lv_out"},
    {MGMSG_PZ_SET_OUTPUTMAXVOLTS, "chan_ident voltage flags"},
    {MGMSG_PZ_GET_OUTPUTMAXVOLTS, "chan_ident voltage flags"},
    {MGMSG_PZ_SET_TPZ_SLEWRATES, "chan_ident slew_open slew_closed"},
    {MGMSG_PZ_GET_TPZ_SLEWRATES, "chan_ident slew_open slew_closed"},
    {MGMSG_PZ_SET_TSG_IOSETTINGS, "chan_ident hub_analogue_output display_mode force_calib future_use1 future_use2 future_use3"},
    {MGMSG_PZ_GET_TSG_IOSETTINGS, "chan_ident hub_analogue_output display_mode force_calib future_use1 future_use2 future_use3"},
    {MGMSG_PZ_SET_POSCONTROLMODE, "chan_ident mode"},
    {MGMSG_PZ_GET_POSCONTROLMODE, "chan_ident mode"},
    {MGMSG_PZ_SET_LUTVALUETYPE, "lut_type"},
    {MGMSG_PZ_GET_PZSTATUSBITS, "chan_ident status_bits"},
    {MGMSG_PZ_GET_PZSTATUSUPDATE, "chan_ident op_voltage position status_bits"},
    {MGMSG_PZ_SET_EEPROMPARAMS, "chan_ident msg_id"},
    {MGMSG_PZ_GET_MAXTRAVEL, "chan_ident travel"},
    {MGMSG_PZ_GET_TSG_READING, "chan_ident reading smoothed"},
    // The K-Cube units' own blocks (later protocol issues, codec_kcube_units.hpp).
    {MGMSG_KPZ_SET_KCUBEMMIPARAMS, "chan_ident js_mode js_volt_gearbox js_volt_step dir_sense preset_volt1 preset_volt2 disp_brightness disp_timeout disp_dim_level reserved1 reserved2 reserved3 reserved4"},
    {MGMSG_KPZ_GET_KCUBEMMIPARAMS, "chan_ident js_mode js_volt_gearbox js_volt_step dir_sense preset_volt1 preset_volt2 disp_brightness disp_timeout disp_dim_level reserved1 reserved2 reserved3 reserved4"},
    {MGMSG_KPZ_SET_KCUBETRIGIOCONFIG, "chan_ident trig1_mode trig1_polarity trig2_mode trig2_polarity reserved1 reserved2 reserved3 reserved4 reserved5 reserved6"},
    {MGMSG_KPZ_GET_KCUBETRIGIOCONFIG, "chan_ident trig1_mode trig1_polarity trig2_mode trig2_polarity reserved1 reserved2 reserved3 reserved4 reserved5 reserved6"},
    {MGMSG_KSG_SET_KCUBEMMIPARAMS, "chan_ident disp_intensity disp_timeout disp_dim_level"},
    {MGMSG_KSG_GET_KCUBEMMIPARAMS, "chan_ident disp_intensity disp_timeout disp_dim_level"},
    {MGMSG_KSG_SET_KCUBETRIGIOCONFIG, "chan_ident trig1_mode trig1_polarity trig2_mode trig2_polarity lower_lim upper_lim smoothing_samples reserved"},
    {MGMSG_KSG_GET_KCUBETRIGIOCONFIG, "chan_ident trig1_mode trig1_polarity trig2_mode trig2_polarity lower_lim upper_lim smoothing_samples reserved"},
    {MGMSG_MOT_GET_STATUSUPDATE, "chan_ident position enc_count status_bits"},
    {MGMSG_MOT_GET_DCSTATUSUPDATE, "chan_ident position velocity reserved status_bits"},
};

const std::unordered_map<std::uint16_t, std::vector<std::string_view>>& names_table()
{
    static const auto table = [] {
        std::unordered_map<std::uint16_t, std::vector<std::string_view>> t;
        for (const auto& [id, names] : kFieldNames) {
            auto& list = t[id];
            for (std::size_t at = 0; at < names.size();) {
                const auto space = std::min(names.find(' ', at), names.size());
                list.push_back(names.substr(at, space - at));
                at = space + 1;
            }
        }
        return t;
    }();
    return table;
}

std::string hex_id(unsigned v, int digits)
{
    char buf[12];
    std::snprintf(buf, sizeof buf, "0x%0*x", digits, v);
    return buf;
}

nlohmann::json value(std::uint8_t v) { return v; }
nlohmann::json value(std::uint16_t v) { return v; }
nlohmann::json value(std::int16_t v) { return v; }
nlohmann::json value(std::uint32_t v) { return v; }
nlohmann::json value(std::int32_t v) { return v; }
nlohmann::json value(const std::optional<std::int32_t>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }
template <std::size_t N> nlohmann::json value(const std::array<char, N>& a)
{
    std::size_t n = 0;
    while (n < N && a[n] != '\0')
        ++n;
    return printable(std::string_view(a.data(), n), N);
}

/// The table naming the bits of message `id`'s status word on `unit`'s wire.
StatusTable table_of(std::uint16_t id, const LogContext& unit)
{
    if (id == MGMSG_RACK_GET_STATUSBITS)
        return StatusTable::Rack;
    if (id == MGMSG_PZ_GET_PZSTATUSUPDATE || id == MGMSG_PZ_GET_PZSTATUSBITS)
        return unit.unit == StatusTable::StrainGauge ? StatusTable::StrainGauge : StatusTable::Piezo;
    return unit.unit == StatusTable::Solenoid ? StatusTable::Solenoid : StatusTable::Motor;
}

/// The status structure of the end-of-move messages (p. 44, p. 50), flattened. The codec reads
/// it as the DC structure (the bytes cannot tell); a stepper's is MOT_GET_STATUSUPDATE's, whose
/// encoder count (a long) fills the DC structure's velocity and reserved words.
void put_status(const msg::MotorStatus& s, const LogContext& unit, StatusTable table, nlohmann::json& fields)
{
    msg::MotStatus st;
    if (const auto* dc = std::get_if<msg::DcStatus>(&s)) {
        if (!unit.stepper_status) {
            fields["chan_ident"] = dc->chan_ident;
            fields["position"] = dc->position;
            fields["velocity"] = dc->velocity;
            fields["status_bits"] = dc->status_bits;
            fields["status_set"] = status_bit_names(dc->status_bits, table);
            return;
        }
        const auto enc = static_cast<std::uint32_t>(static_cast<std::uint16_t>(dc->velocity))
                         | static_cast<std::uint32_t>(dc->reserved) << 16;
        st = {dc->chan_ident, dc->position, static_cast<std::int32_t>(enc), dc->status_bits};
    } else {
        st = std::get<msg::MotStatus>(s);
    }
    fields["chan_ident"] = st.chan_ident;
    fields["position"] = st.position;
    fields["enc_count"] = st.enc_count;
    fields["status_bits"] = st.status_bits;
    fields["status_set"] = status_bit_names(st.status_bits, table);
}

template <class T> void put_fields(const T& m, std::uint16_t id, const LogContext& unit, nlohmann::json& fields)
{
    auto values = nlohmann::json::array();
    bool status = false;
    std::apply(
        [&](const auto&... f) {
            [[maybe_unused]] auto one = [&](const auto& v) {
                if constexpr (std::is_same_v<std::decay_t<decltype(v)>, msg::MotorStatus>) {
                    put_status(v, unit, table_of(id, unit), fields);
                    status = true;
                } else {
                    values.push_back(value(v));
                }
            };
            (one(f), ...);
        },
        T::fields(m));
    if (status)
        return;
    const auto* names = field_names(id);
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (names && names->size() == values.size())
            fields[std::string((*names)[i])] = values[i];
        else if (values.size() == 1 && !names)
            fields["chan_ident"] = values[i];
        else
            fields["field" + std::to_string(i + 1)] = values[i];
    }
    if (const auto bits = fields.find("status_bits"); bits != fields.end() && bits->is_number_unsigned())
        fields["status_set"] = status_bit_names(bits->get<std::uint32_t>(), table_of(id, unit));
}

} // namespace

const std::vector<std::string_view>* field_names(std::uint16_t id)
{
    const auto& t = names_table();
    const auto it = t.find(id);
    return it == t.end() ? nullptr : &it->second;
}

namespace {

using BitNames = std::vector<std::pair<std::uint32_t, std::string_view>>;

const BitNames& bit_names(StatusTable table)
{
    // MOT_GET_STATUSUPDATE / MOT_GET_DCSTATUSUPDATE (p. 78-79; ERRATA for 0x00000008).
    static const BitNames motor{
        {0x00000001, "forward_hard_limit"}, {0x00000002, "reverse_hard_limit"},
        {0x00000004, "forward_soft_limit"}, {0x00000008, "reverse_soft_limit"},
        {0x00000010, "moving_forward"},     {0x00000020, "moving_reverse"},
        {0x00000040, "jogging_forward"},    {0x00000080, "jogging_reverse"},
        {0x00000100, "motor_connected"},    {0x00000200, "homing"},
        {0x00000400, "homed"},              {0x00001000, "interlock"},
        {0x00002000, "settled"},            {0x00004000, "motion_error"},
        {0x01000000, "current_limit"},      {0x80000000, "enabled"},
    };
    // A solenoid unit's (D-4): the output (the bit Kinesis reads from a KSC101), the interlock
    // mode (p. 77), the key switch (msl-equipment ksc.py is_key_unlocked, bit 13).
    static const BitNames solenoid{{0x00000001, "output_on"}, {0x00001000, "interlock"}, {0x00002000, "key_unlocked"}};
    // PZ_GET_PZSTATUSBITS / PZSTATUSUPDATE (p. 101-104): the TPZ001's table and the BPC's, which
    // adds the hardware voltage range, the digital inputs, active and enabled.
    static const BitNames piezo{
        {0x00000001, "actuator_connected"}, {0x00000010, "zeroed"},          {0x00000020, "zeroing"},
        {0x00000100, "gauge_connected"},    {0x00000400, "closed_loop"},     {0x00001000, "hw_max_75v"},
        {0x00002000, "hw_max_100v"},        {0x00004000, "hw_max_150v"},     {0x00100000, "digital_input_1"},
        {0x00200000, "digital_input_2"},    {0x00400000, "digital_input_3"}, {0x00800000, "digital_input_4"},
        {0x01000000, "digital_input_5"},    {0x02000000, "digital_input_6"}, {0x04000000, "digital_input_7"},
        {0x08000000, "digital_input_8"},    {0x20000000, "active"},          {0x80000000, "enabled"},
    };
    // A strain gauge reader's reading of the piezo table (strain_gauge_module.hpp): bit 0 is its gauge.
    static const BitNames gauge{{0x00000001, "gauge_connected"}, {0x00000010, "zeroed"}, {0x00000020, "zeroing"}};
    // RACK_GET_STATUSBITS (p. 25): the USER IO lines ("inputs" in its text, "Digital output N
    // state" in its table).
    static const BitNames rack{{0x1, "user_io_1"}, {0x2, "user_io_2"}, {0x4, "user_io_3"}, {0x8, "user_io_4"}};
    switch (table) {
    case StatusTable::Motor:
        return motor;
    case StatusTable::Solenoid:
        return solenoid;
    case StatusTable::Piezo:
        return piezo;
    case StatusTable::StrainGauge:
        return gauge;
    case StatusTable::Rack:
        return rack;
    }
    return motor;
}

} // namespace

/// What the wire log must know of `model` to name the fields of its frames.
LogContext log_context(const ControllerModel& model)
{
    LogContext c;
    c.stepper_status = model.kind == UnitKind::Motor && model.motor == MotorKind::Stepper;
    switch (model.kind) {
    case UnitKind::Motor:
        c.unit = StatusTable::Motor;
        break;
    case UnitKind::Solenoid:
        c.unit = StatusTable::Solenoid;
        break;
    case UnitKind::Piezo:
        c.unit = StatusTable::Piezo;
        break;
    case UnitKind::StrainGauge:
        c.unit = StatusTable::StrainGauge;
        break;
    }
    return c;
}

std::vector<std::string_view> status_bit_names(std::uint32_t bits, StatusTable table)
{
    std::vector<std::string_view> out;
    for (const auto& [bit, name] : bit_names(table))
        if (bits & bit)
            out.push_back(name);
    return out;
}

void decode_for_log(std::string_view bytes, nlohmann::json& out, const LogContext& unit)
{
    FrameFramer framer;
    const auto r = framer.parse(bytes);
    if (r.status != FrameFramer::Status::Frame || r.dropped != 0) {
        out["name"] = "not a frame";
        return;
    }
    const Frame& f = r.frame;
    out["id"] = hex_id(f.id, 4);
    out["name"] = f.info ? std::string(f.info->name) : hex_id(f.id, 4);
    out["source"] = hex_id(f.source, 2);
    out["destination"] = hex_id(f.dest, 2);
    auto fields = nlohmann::json::object();
    msg::visit(
        [&](const auto& m) {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, msg::Untyped>) {
                if (m.has_data)
                    fields["data"] = hex_bytes(m.data);
                else {
                    fields["param1"] = m.param1;
                    fields["param2"] = m.param2;
                }
            } else {
                put_fields(m, f.id, unit, fields);
            }
        },
        msg::decode(f));
    out["fields"] = std::move(fields);
}

} // namespace rigsim::apt
