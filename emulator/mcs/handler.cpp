#include "emulator/mcs/handler.hpp"
#include "emulator/mcs/handler_replies.hpp"

#include <string>

namespace rigsim::mcs {

using replies::join;
using replies::result;

Error Handler::missing(std::int32_t index) const
{
    // An index that names no channel is a system error: no channel generated it (manual
    // 1.1: "-1 ... the error does not originate from a specific channel"). A channel of
    // the other type (positioner command to an end effector, or the reverse) answers 7.
    if (controller_.valid_index(index))
        return Error{index, ErrorCode::InvalidParameter};
    return Error{kSystem, ErrorCode::InvalidParameter};
}

bool Handler::take_reset_request()
{
    const bool r = reset_requested_;
    reset_requested_ = false;
    return r;
}

Reply Handler::handle(const Command& command)
{
    // 2.4.5: after ATC the channel's next command goes to its queue if it is a movement
    // (152 otherwise); with a command queued, immediate movements answer 151.
    if (const auto index = channel_of(command)) {
        if (auto* ch = controller_.channel(*index)) {
            if (ch->armed_queue_source()) {
                if (!is_movement(command)) {
                    ch->disarm_queue();
                    return Error{*index, ErrorCode::CommandNotTriggerable};
                }
                if (auto err = ch->enqueue(command))
                    return Error{*index, *err};
                return Silent{};
            }
            if (ch->queue_size() > 0 && is_movement(command))
                return Error{*index, ErrorCode::WaitingForTrigger};
        }
    }
    return execute(command);
}

Reply Handler::execute(const Command& command)
{
    return std::visit([this](const auto& c) { return on(c); }, command);
}

/// GNC: number of channels (3.1).
Reply Handler::on(const GetNumberOfChannels&)
{
    return Answer{join("N", static_cast<std::int64_t>(controller_.channel_count()))};
}

/// GSI: system id (3.1).
Reply Handler::on(const GetSystemId&)
{
    return Answer{join("ID", controller_.system_id())};
}

/// GIV: interface version, RS232 form `IV<high>,<low>,<update>` (3.1).
Reply Handler::on(const GetInterfaceVersion&)
{
    const auto v = controller_.interface_version();
    return Answer{join("IV", v.high, v.low) + ',' + std::to_string(v.update)};
}

/// GCT<ch>: channel type, 0 positioner, 1 end effector (3.1).
Reply Handler::on(const GetChannelType& c)
{
    if (controller_.effector(c.channel))
        return Answer{join("CT", c.channel, static_cast<int>(ChannelType::EndEffector))};
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return Answer{join("CT", c.channel, static_cast<int>(ch->type()))};
}

/// GST<ch>: sensor type code of appendix 4.3 (3.2).
Reply Handler::on(const GetSensorType& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (!ch->sensor())
        return Error{c.channel, ErrorCode::NoSensorPresent};
    return Answer{join("ST", c.channel, ch->sensor()->code)};
}

/// SST<ch>,<type>: set sensor type; stops the positioner (3.2).
Reply Handler::on(const SetSensorType& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (!ch->sensor())
        return Error{c.channel, ErrorCode::NoSensorPresent};
    if (auto err = ch->set_sensor_type(c.type_code))
        return Error{c.channel, *err};
    return Ack{c.channel};
}

/// GP<ch>: position in nm, linear sensors only (3.4).
Reply Handler::on(const GetPosition& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_linear_sensor())
        return Error{c.channel, *err};
    return Answer{join("P", c.channel, ch->position_nm())};
}

/// GS<ch>: channel status code of appendix 4.1 (3.4).
Reply Handler::on(const GetStatus& c)
{
    if (const auto* ee = controller_.effector(c.channel))
        return Answer{join("S", c.channel, static_cast<int>(ee->status()))};
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return Answer{join("S", c.channel, static_cast<int>(ch->status()))};
}

/// MPA<ch>,<position_nm>,<hold_ms>: move to position absolute (3.3).
Reply Handler::on(const MovePositionAbsolute& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_linear_sensor())
        return Error{c.channel, *err};
    if (auto err = ch->move_absolute(c.position_nm, c.hold_ms))
        return Error{c.channel, *err};
    return Ack{c.channel};
}

/// MPR<ch>,<distance_nm>,<hold_ms>: move to position relative (3.3).
Reply Handler::on(const MovePositionRelative& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_linear_sensor())
        return Error{c.channel, *err};
    if (auto err = ch->move_relative(c.distance_nm, c.hold_ms))
        return Error{c.channel, *err};
    return Ack{c.channel};
}

/// S[<ch>]: stop one channel, or all when the index is omitted (3.3).
Reply Handler::on(const Stop& c)
{
    if (!c.channel) {
        controller_.stop_all();
        return Ack{kSystem};
    }
    if (auto* ee = controller_.effector(*c.channel)) {
        ee->stop();
        return Ack{*c.channel};
    }
    auto* ch = controller_.channel(*c.channel);
    if (!ch)
        return missing(*c.channel);
    ch->stop();
    return Ack{*c.channel};
}

/// SCLS<ch>,<speed>: closed-loop speed; the manual documents the acknowledge as E-1,0 (3.2).
Reply Handler::on(const SetClosedLoopSpeed& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->set_closed_loop_speed(c.speed))
        return Error{c.channel, *err};
    return Ack{kSystem};
}

/// GCLS<ch>: closed-loop speed (3.2).
Reply Handler::on(const GetClosedLoopSpeed& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return Answer{join("CLS", c.channel, ch->closed_loop_speed())};
}

/// SCLA<ch>,<acceleration>: closed-loop acceleration in µm/s² (3.2).
Reply Handler::on(const SetClosedLoopAcceleration& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->set_closed_loop_acceleration(c.acceleration))
        return Error{c.channel, *err};
    return Ack{c.channel};
}

/// GCLA<ch>: closed-loop acceleration (3.2).
Reply Handler::on(const GetClosedLoopAcceleration& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return Answer{join("CLA", c.channel, ch->closed_loop_acceleration())};
}

/// GCM: communication mode, 0 sync, 1 async (3.1).
Reply Handler::on(const GetCommunicationMode&)
{
    return Answer{join("CM", static_cast<int>(controller_.communication_mode()))};
}

/// SCM<mode>: answers in the new mode: E-1,0 in sync mode, nothing in async (3.1).
Reply Handler::on(const SetCommunicationMode& c)
{
    if (c.mode != 0 && c.mode != 1)
        return Error{kSystem, ErrorCode::InvalidParameter};
    controller_.set_communication_mode(static_cast<CommunicationMode>(c.mode));
    return Ack{kSystem};
}

/// R: acknowledge, then the power-down/power-up (3.1).
Reply Handler::on(const Reset&)
{
    reset_requested_ = true;
    return Ack{kSystem};
}

/// SHE<mode>: hand control module 0 disabled, 1 enabled, 2 display only (3.1).
Reply Handler::on(const SetHcmEnabled& c)
{
    if (c.mode < 0 || c.mode > 2)
        return Error{kSystem, ErrorCode::InvalidParameter};
    controller_.set_hcm_mode(c.mode);
    return Ack{kSystem};
}

/// GSE: system sensor mode (3.2).
Reply Handler::on(const GetSensorEnabled&)
{
    return Answer{join("SE", static_cast<int>(controller_.sensor_mode()))};
}

/// SSE<mode>: sensors disabled/enabled/power save; stops every positioner (3.2).
Reply Handler::on(const SetSensorEnabled& c)
{
    if (c.mode < 0 || c.mode > 2)
        return Error{kSystem, ErrorCode::InvalidParameter};
    controller_.set_sensor_mode(static_cast<SensorMode>(c.mode));
    return Ack{kSystem};
}

/// GPPK<ch>: physical position known (3.4).
Reply Handler::on(const GetPhysicalPositionKnown& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (!ch->sensor())
        return Error{c.channel, ErrorCode::NoSensorPresent};
    return Answer{join("PPK", c.channel, ch->physical_position_known() ? 1 : 0)};
}

/// SCLF<ch>,<frequency>: maximum closed-loop driving frequency 50..18500 Hz (3.2).
Reply Handler::on(const SetClosedLoopMaxFrequency& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->set_closed_loop_max_frequency(c.frequency_hz), c.channel, c.channel);
}

/// SARP<ch>,<accumulate>: accumulate relative targets (3.2).
Reply Handler::on(const SetAccumulateRelativePositions& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->set_accumulate_relative(c.accumulate), c.channel, c.channel);
}

/// SP<ch>,<position>: define the current position (3.2, 2.3.3).
Reply Handler::on(const SetPosition& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->set_position(c.position), c.channel, c.channel);
}

/// SZP<ch>: deprecated form of SP<ch>,0 (3.2).
Reply Handler::on(const SetZeroPosition& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->set_position(0), c.channel, c.channel);
}

/// SSC<ch>,<scale>,<inverted>: acknowledged as E-1,0 per the manual (3.2).
Reply Handler::on(const SetScale& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (!ch->sensor())
        return Error{c.channel, ErrorCode::NoSensorPresent};
    return result(ch->set_scale(c.scale, c.inverted), c.channel, kSystem);
}

/// GSC<ch>: `SC<ch>,<scale>,<inverted>` (3.2).
Reply Handler::on(const GetScale& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (!ch->sensor())
        return Error{c.channel, ErrorCode::NoSensorPresent};
    return Answer{join("SC", c.channel, ch->scale_offset()) + (ch->scale_inverted() ? ",1" : ",0")};
}

/// SSD<ch>,<direction>: safe direction; acknowledged as E-1,0 per the manual (3.2).
Reply Handler::on(const SetSafeDirection& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->set_safe_direction(c.direction), c.channel, kSystem);
}

/// GSD<ch>: `SD<ch>,<direction>` (3.2).
Reply Handler::on(const GetSafeDirection& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return Answer{join("SD", c.channel, ch->safe_direction())};
}

/// SSWS<ch>,<step>: allow steps while holding a position (3.2).
Reply Handler::on(const SetStepWhileScan& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->set_step_while_scan(c.step), c.channel, c.channel);
}

/// SRC<ch>,<report>: asynchronous mode only (8 in sync mode); no answer (3.2).
Reply Handler::on(const SetReportOnComplete& c)
{
    if (controller_.communication_mode() != CommunicationMode::Async)
        return Error{kSystem, ErrorCode::WrongMode};
    if (controller_.effector(c.channel)) {
        if (c.report != 0 && c.report != 1)
            return Error{c.channel, ErrorCode::InvalidParameter};
        controller_.set_effector_report(c.channel, c.report == 1);
        return Silent{};
    }
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (c.report != 0 && c.report != 1)
        return Error{c.channel, ErrorCode::InvalidParameter};
    ch->set_report_on_complete(c.report == 1);
    return Silent{};
}

/// K[<delay>]: keep-alive timeout 100..60000 ms or 0 (off); without a parameter it only
/// resets the counter (3.5).
Reply Handler::on(const KeepAlive& c)
{
    if (c.delay_ms) {
        if (*c.delay_ms != 0 && (*c.delay_ms < 100 || *c.delay_ms > 60'000))
            return Error{kSystem, ErrorCode::InvalidParameter};
        controller_.set_keep_alive(*c.delay_ms);
    }
    return Ack{kSystem};
}

/// CB<baudrate>: 9600..115200; `BR<effective rate>`, in effect after the next reset (3.5).
Reply Handler::on(const ConfigureBaudrate& c)
{
    if (c.baudrate < 9600 || c.baudrate > 115'200)
        return Error{kSystem, ErrorCode::InvalidParameter};
    return Answer{join("BR", controller_.configure_baudrate(c.baudrate))};
}

/// GSN<ch>: `SN<ch>,0x<hex>`, unique per channel (3.5).
Reply Handler::on(const GetSerialNumber& c)
{
    if (!controller_.valid_index(c.channel))
        return missing(c.channel);
    static constexpr char kHex[] = "0123456789abcdef";
    const std::uint64_t serial = (static_cast<std::uint64_t>(controller_.system_id()) << 8) | static_cast<unsigned>(c.channel);
    std::string hex;
    for (int shift = 28; shift >= 0; shift -= 4)
        hex += kHex[(serial >> shift) & 0xf];
    return Answer{join("SN", c.channel) + ",0x" + hex};
}

/// GFV<ch>: signal controller (type 2) and signal generator (type 3) versions (3.5).
Reply Handler::on(const GetFirmwareVersion& c)
{
    if (!controller_.valid_index(c.channel))
        return missing(c.channel);
    const auto v = controller_.firmware_version();
    const std::string version = std::to_string(v.high) + "," + std::to_string(v.low) + "," + std::to_string(v.update);
    if (controller_.effector(c.channel))   // device type 9: end effector module
        return Answer{join("FV", c.channel) + ",9," + version + ",9," + version};
    return Answer{join("FV", c.channel) + ",2," + version + ",3," + version};
}

/// GFP<ch>,<byte>: feature permission bytes; 255 asks for their number (3.5).
/// One byte; bit 0 (low vibration) is clear: permitted. Other bits set: not permitted.
Reply Handler::on(const GetFeaturePermissions& c)
{
    if (!controller_.valid_index(c.channel))
        return missing(c.channel);
    if (c.byte_index == 255)
        return Answer{join("FP", c.channel, 1)};
    if (c.byte_index != 0)
        return Error{c.channel, ErrorCode::InvalidParameter};
    return Answer{join("FP", c.channel, 254)};
}

/// FRM<ch>,<direction>,<hold>,<autoZero>: find the reference (3.3, 2.3.3); status 7.
Reply Handler::on(const FindReferenceMark& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->find_reference(c.direction, c.hold_ms, c.auto_zero), c.channel, c.channel);
}

/// CS<ch>: calibrate the sensor; status 6 for a few seconds (3.3).
Reply Handler::on(const CalibrateSensor& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->calibrate(), c.channel, c.channel);
}

/// SPL<ch>,<min>,<max>: linear software range limit (3.2, 2.3.4).
Reply Handler::on(const SetPositionLimit& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_linear_sensor())
        return Error{c.channel, *err};
    return result(ch->set_range_limit(c.min_nm, c.max_nm), c.channel, c.channel);
}

/// GPL<ch>: `PL<ch>,<min>,<max>` (0,0: no limit) (3.2).
Reply Handler::on(const GetPositionLimit& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (auto err = ch->check_linear_sensor())
        return Error{c.channel, *err};
    const auto [lo, hi] = ch->range_limit();
    return Answer{join("PL", c.channel, lo) + "," + std::to_string(hi)};
}

/// GCP<ch>,<key>: `CPR<ch>,<key>,<value>` (3.2, appendix 4.4).
Reply Handler::on(const GetChannelProperty& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    std::int64_t value = 0;
    if (auto err = ch->get_property(static_cast<std::uint32_t>(c.key), value))
        return Error{c.channel, *err};
    return Answer{join("CPR", c.channel, c.key) + "," + std::to_string(value)};
}

/// SCP<ch>,<key>,<value>: acknowledged as E-1,0 per the manual (3.2, appendix 4.4).
Reply Handler::on(const SetChannelProperty& c)
{
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    return result(ch->set_property(static_cast<std::uint32_t>(c.key), c.value), c.channel, kSystem);
}

/// GESM: `ESM<mode>` (deprecated, 3.2).
Reply Handler::on(const GetEmergencyStopMode&)
{
    return Answer{join("ESM", controller_.emergency_stop_mode())};
}

/// SESM<mode>: 0 normal, 1 restricted, 2 disabled for every channel; unlocks (3.2).
Reply Handler::on(const SetEmergencyStopMode& c)
{
    if (c.mode < 0 || c.mode > 2)
        return Error{kSystem, ErrorCode::InvalidParameter};
    controller_.set_emergency_stop_mode(c.mode);
    return Ack{kSystem};
}

/// ATC<ch>,<source>: queue the channel's next movement command (async only, 3.3, 2.4.5).
Reply Handler::on(const AppendTriggeredCommand& c)
{
    if (controller_.communication_mode() != CommunicationMode::Async)
        return Error{kSystem, ErrorCode::WrongMode};
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    const bool valid = c.trigger_source == 512 || c.trigger_source == 513
        || (c.trigger_source >= 1792 && c.trigger_source <= 2047);   // 4.4.1, 0 not allowed
    if (!valid)
        return Error{c.channel, ErrorCode::InvalidParameter};
    if (ch->queue_size() >= Channel::kQueueCapacity)
        return Error{c.channel, ErrorCode::CommandQueueFull};
    ch->arm_queue(c.trigger_source);
    return Silent{};
}

/// CTCQ<ch>: drop the queued commands (async only, 3.3).
Reply Handler::on(const ClearTriggeredCommandQueue& c)
{
    if (controller_.communication_mode() != CommunicationMode::Async)
        return Error{kSystem, ErrorCode::WrongMode};
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    ch->clear_queue();
    return Silent{};
}

/// TC<index>: software trigger 0..255 to every channel (async only, 3.3, 2.4.2).
Reply Handler::on(const TriggerCommand& c)
{
    if (controller_.communication_mode() != CommunicationMode::Async)
        return Error{kSystem, ErrorCode::WrongMode};
    if (c.trigger_index < 0 || c.trigger_index > 255)
        return Error{kSystem, ErrorCode::InvalidParameter};
    controller_.trigger(1792 + c.trigger_index);
    return Silent{};
}

/// SRT<ch>,<report>: report T<ch> when a queued command is triggered (async only, 3.2).
Reply Handler::on(const SetReportOnTriggered& c)
{
    if (controller_.communication_mode() != CommunicationMode::Async)
        return Error{kSystem, ErrorCode::WrongMode};
    auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (c.report != 0 && c.report != 1)
        return Error{c.channel, ErrorCode::InvalidParameter};
    ch->set_report_on_triggered(c.report == 1);
    return Silent{};
}

/// GB<ch>,<buffer>: `CB<ch>,0,<position>,<revolution>,<counter>` (3.4, 2.4.4).
Reply Handler::on(const GetCaptureBuffer& c)
{
    const auto* ch = controller_.channel(c.channel);
    if (!ch)
        return missing(c.channel);
    if (c.buffer != 0)
        return Error{c.channel, ErrorCode::InvalidParameter};
    const auto b = ch->capture_buffer();
    return Answer{join("CB", c.channel, 0) + "," + std::to_string(b[0]) + "," + std::to_string(b[1]) + ","
                  + std::to_string(b[2])};
}

} // namespace rigsim::mcs
