#include "emulator/mcs2/controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

// The switches over Id below handle the rows with behaviour of their own and leave the others to
// the table's generic handling (their default): listing ~130 ids in each would hide that.
#pragma GCC diagnostic ignored "-Wswitch-enum"

namespace rigsim::mcs2 {

namespace {

/// A string answer: quoted, as units answer (`"MCS2-00013416"`, slaclab/pyMCS2's and BLISS's
/// logs of real units), a quote inside doubled (SCPI).
std::string quote_string(std::string_view s)
{
    std::string out = "\"";
    for (const char c : s) {
        out += c;
        if (c == '"')
            out += '"';
    }
    out += '"';
    return out;
}

/// An I32 property reads as a signed 32-bit number (Hold Time's 0xffffffff reads -1), but for
/// those whose range the guide gives past 2^31 (Pulse Width, ESD Counter Threshold: up to 4×10^9),
/// which read as the unsigned number written.
std::string number(const Property& p, std::int64_t v)
{
    const auto bits = static_cast<std::uint32_t>(static_cast<std::uint64_t>(v));
    if (p.type == Type::I32 && p.id != Id::HoldTime && p.max > std::numeric_limits<std::int32_t>::max())
        return std::to_string(bits);
    if (p.type == Type::I32)
        return std::to_string(static_cast<std::int32_t>(bits));
    return std::to_string(v);
}

bool readable(Access a)
{
    return a != Access::W;
}

bool writable(Access a)
{
    return a != Access::R;
}

bool later_only(Id id)
{
    return id == Id::SensorModeAlias || id == Id::SensorDelayAlias || id == Id::ModuleStateAlias ||
           id == Id::FollowingError;
}

constexpr std::size_t kTuningFirst = static_cast<std::size_t>(Id::TunMovementType);

} // namespace

// ---- error queue ----

void ErrorQueue::push(std::int32_t code, std::string_view text)
{
    if (entries_.size() >= kDepth) {
        entries_.back() = Entry{static_cast<std::int32_t>(ScpiError::QueueOverflow),
                                std::string(scpi_error_text(ScpiError::QueueOverflow))};
        return;
    }
    entries_.push_back(Entry{code, std::string(text)});
}

ErrorQueue::Entry ErrorQueue::next()
{
    if (entries_.empty())
        return Entry{0, "No Error"};
    auto e = std::move(entries_.front());
    entries_.pop_front();
    return e;
}

// ---- controller ----

Controller::Controller(const Config& config, models::World& world, const std::string& name)
    : config_(config), clock_(world.clock())
{
    for (std::size_t i = 0; i < config_.channels.size(); ++i)
        channels_.push_back(
            std::make_unique<Channel>(static_cast<int>(i), config_.channels[i], world, name + "/" + std::to_string(i)));
    channel_store_.assign(channels_.size(), std::vector<std::int64_t>(table().size(), 0));
    device_store_.assign(table().size(), 0);
    module_power_.assign(module_count(), true);
    started_by_.assign(channels_.size(), nullptr);
    io_.assign(module_count(), IoModule{});
    restore_defaults();
}

Controller::~Controller() = default;

void Controller::restore_defaults()
{
    for (auto& c : channels_)
        c->restore_defaults();
    // Every channel row's cell (the stored rows' values, and the live rows kept in the store:
    // Sensor Input Select, Signal Correction Options, Output Trigger Mode) and the device's.
    for (const auto& p : table()) {
        const auto row = static_cast<std::size_t>(p.id);
        if (p.scope == Scope::Channel)
            for (auto& store : channel_store_)
                store[row] = p.initial;
        else if (p.kind == Kind::Stored)
            device_store_[row] = p.initial;
    }
    std::fill(io_.begin(), io_.end(), IoModule{});
    device_name_ = config_.serial_number;   // "default = the serial number string" (4.2.5)
    power_up();
}

void Controller::power_up()
{
    for (auto& c : channels_)
        c->power_up();
    for (const auto& p : table()) {   // volatile properties back to their power-up values
        if (p.nonvolatile)
            continue;
        const auto row = static_cast<std::size_t>(p.id);
        if (p.scope == Scope::Channel)
            for (auto& store : channel_store_)
                store[row] = p.initial;
        else if (p.kind == Kind::Stored)
            device_store_[row] = p.initial;
    }
    // The Max Closed Loop Frequency starts at its stored default (4.4.17-4.4.18).
    for (std::size_t i = 0; i < channels_.size(); ++i)
        channels_[i]->settings().max_frequency = stored_channel(i, Id::MaxFrequencyDefault);
    std::fill(module_power_.begin(), module_power_.end(), true);
    estop_mode_ = 0;
    group_owner_ = nullptr;
    group_.clear();
    group_finished_ = false;
    group_values_.clear();
    group_external_ = false;
    group_armed_ = nullptr;
    for (const auto ch : stream_.channels)
        channels_[ch]->set_streaming(false);
    stream_ = Stream{};
    trigger_mode_ = 0;
    trigger_condition_ = 0;
    set_locked(false);
    for (auto& io : io_) {   // the analog input range is non-volatile (4.12.3)
        const auto range = io.ain_range;
        io = IoModule{};
        io.ain_range = range;
    }
}

std::uint32_t Controller::device_state() const
{
    // No hand control module; MOVEMENT_LOCKED after an emergency stop (with an I/O module).
    return (locked_ ? 0x0002u : 0u) | (stream_.running ? 0x1000u : 0u);   // IS_STREAMING (2.8.1)
}

std::uint32_t Controller::module_state(std::size_t module) const
{
    (void)module;
    // SM_PRESENT: each driver module has its sensor module; IOM_PRESENT with the I/O module.
    return 0x0001u | (config_.io_module ? 0x0008u : 0u);
}

std::uint32_t Controller::channel_state(std::size_t i) const
{
    auto s = channels_[i]->state_word();
    if (config_.firmware == Firmware::Current && channels_[i]->amplifier())
        s |= 1u << 18;   // AMPLIFIER_ENABLED (later firmware; EPICS motorSmarAct reads it as "power on")
    return s;
}

void Controller::forget(const SessionState& session)
{
    if (group_owner_ == &session || group_armed_ == &session) {
        group_owner_ = nullptr;
        group_armed_ = nullptr;
        group_.clear();
    }
    if (stream_.open && stream_.owner == &session)
        stream_abort(Error::Aborted);
    for (std::size_t i = 0; i < channels_.size(); ++i) {
        if (started_by_[i] != &session)
            continue;
        started_by_[i] = nullptr;
        if (channels_[i]->moving())
            channels_[i]->stop();
    }
}

Controller::Result Controller::execute(std::string_view message, SessionState& s)
{
    Result r;
    std::vector<std::string> answers;
    CommandTree::Level level;
    const auto& tree = command_tree();
    for (const auto& c : parse_message(message)) {
        if (c.error != ScpiError::None) {
            s.errors.push(static_cast<std::int32_t>(c.error), scpi_error_text(c.error));
            ++r.errors;
            continue;
        }
        const auto found = tree.resolve(c, level);
        const Property* p = found ? node_property(found->node) : nullptr;
        if (p && later_only(p->id) && config_.firmware != Firmware::Current)
            p = nullptr;
        if (!p) {
            s.errors.push(static_cast<std::int32_t>(ScpiError::UndefinedHeader),
                          scpi_error_text(ScpiError::UndefinedHeader));
            ++r.errors;
            continue;
        }
        run(*p, found->indices, c, s, answers, r);
        if (r.reset)
            break;
    }
    if (!answers.empty()) {
        r.answered = true;
        for (std::size_t i = 0; i < answers.size(); ++i) {
            if (i)
                r.answer += "; ";   // the guide's examples: `300; 2` (6.2.4)
            r.answer += answers[i];
        }
    }
    return r;
}

void Controller::run(const Property& p, const std::vector<std::int64_t>& indices, const Command& c, SessionState& s,
                     std::vector<std::string>& answers, Result& r)
{
    const auto error = [&](std::int32_t code, std::string_view text) {
        s.errors.push(code, text);
        ++r.errors;
    };
    const auto scpi = [&](ScpiError e) { error(static_cast<std::int32_t>(e), scpi_error_text(e)); };
    // Access: a query of a command without one, a setting of a query-only property.
    if (c.query ? !readable(p.access) : !writable(p.access))
        return scpi(ScpiError::UndefinedHeader);
    if (c.query && !c.params.empty())
        return scpi(ScpiError::ParameterNotAllowed);
    if (!c.query) {
        if (p.type == Type::None && !c.params.empty())
            return scpi(ScpiError::ParameterNotAllowed);
        if (p.type != Type::None && c.params.empty())
            return scpi(ScpiError::MissingParameter);
        if (p.type != Type::None && p.id != Id::StrFrame && c.params.size() > 1)
            return scpi(ScpiError::ParameterNotAllowed);
        if ((p.type == Type::I32 || p.type == Type::I64))
            for (const auto& param : c.params)
                if (param.kind != Param::Kind::Integer)
                    return scpi(ScpiError::DataTypeError);
        if (p.type == Type::String && c.params[0].kind != Param::Kind::String)
            return scpi(ScpiError::DataTypeError);
    }
    // Indices.
    if ((p.scope == Scope::Channel || p.scope == Scope::Command) &&
        (indices.empty() || indices[0] < 0 || static_cast<std::size_t>(indices[0]) >= channels_.size()))
        return error(static_cast<std::int32_t>(Error::InvalidChannelIndex), error_text(0x0022));
    if (p.scope == Scope::Module &&
        (indices.empty() || indices[0] < 0 || static_cast<std::size_t>(indices[0]) >= module_count()))
        return error(static_cast<std::int32_t>(Error::InvalidModuleIndex), error_text(0x0021));
    if (indices.size() > 1 && (indices[1] < 0 || indices[1] > 1))   // AOUT value 0/1, INPut value 0/1
        return error(static_cast<std::int32_t>(Error::InvalidParameter), error_text(0x0013));

    // A command group holds this session's commands until it is closed (6.4).
    if (group_owner_ == &s && p.scope != Scope::Group && p.scope != Scope::System && p.scope != Scope::Common) {
        if (!p.groupable)
            return error(static_cast<std::int32_t>(Error::CommandNotGroupable), error_text(0x0024));
        if (group_.size() >= kMaxGroupCommands)
            return error(static_cast<std::int32_t>(Error::BufferOverflow), error_text(0x000d));
        group_.push_back(Grouped{&p, indices, c});
        group_.back().command.text = {};   // the message it points into is gone when the group runs
        return;
    }

    if (c.query) {
        std::string out;
        if (const auto e = read(p, indices, out); e)
            return error(static_cast<std::int32_t>(*e), error_text(static_cast<std::int32_t>(*e)));
        if (p.id == Id::ErrNext) {
            const auto entry = s.errors.next();
            out = std::to_string(entry.code) + "," + quote_string(entry.text);
        } else if (p.id == Id::ErrCount) {
            out = std::to_string(s.errors.count());
        } else if (p.id == Id::Ese) {
            out = std::to_string(s.ese);
        } else if (p.id == Id::Sre) {
            out = std::to_string(s.sre);
        } else if (p.id == Id::Stb) {
            out = std::to_string(s.errors.count() ? 0x04 : 0);   // SCPI's error/event queue bit
        }
        std::size_t size = out.size();
        for (const auto& a : answers)
            size += a.size() + 2;
        if (size > kMaxAnswer)   // one message's answer is bounded (64 :CGR:VAL? of 256 values would not be)
            return error(static_cast<std::int32_t>(Error::BufferOverflow), error_text(0x000d));
        answers.push_back(std::move(out));
        return;
    }
    if (const auto e = write(p, indices, c, s, r); e)
        return error(static_cast<std::int32_t>(*e), error_text(static_cast<std::int32_t>(*e)));
}

std::optional<Error> Controller::read(const Property& p, const std::vector<std::int64_t>& indices, std::string& out)
{
    switch (p.id) {
    case Id::Esr:
    case Id::Tst:
        out = "0";   // "no effect" (Table 6.1): no event, the self-test passes
        return std::nullopt;
    case Id::Opc:
        out = "1";   // "always returns 1"
        return std::nullopt;
    case Id::Idn:
        out = "SmarAct GmbH,MCS2," + config_.serial_number + "," +
              (config_.firmware == Firmware::Current ? "current" : "1.0.6");
        return std::nullopt;
    case Id::ErrCount:
    case Id::ErrNext:
    case Id::Ese:
    case Id::Sre:
    case Id::Stb:
        return std::nullopt;   // the session's: run() fills them in
    case Id::CgrFinished:
        out = group_finished_ || (!group_owner_ && !group_armed_ && group_.empty()) ? "1" : "0";
        return std::nullopt;
    case Id::CgrValues:
        for (std::size_t i = 0; i < group_values_.size(); ++i)
            out += (i ? "; " : "") + group_values_[i];
        return std::nullopt;
    case Id::StrFree: {
        if (!stream_.open)
            return Error::InvalidStreamHandle;
        std::size_t used = 0;
        for (const auto& f : stream_.frames)
            used += f.size();
        out = std::to_string(kStreamBuffer - used);   // in positions, not frames (6.5.1)
        return std::nullopt;
    }
    case Id::DevChannels:
        out = std::to_string(channels_.size());
        return std::nullopt;
    case Id::DevModules:
        out = std::to_string(module_count());
        return std::nullopt;
    case Id::DevState:
        out = std::to_string(device_state());
        return std::nullopt;
    case Id::DevSerial:
        out = quote_string(config_.serial_number);
        return std::nullopt;
    case Id::DevName:
        out = quote_string(device_name_);
        return std::nullopt;
    case Id::DevEstopMode:
        out = std::to_string(estop_mode_);
        return std::nullopt;
    case Id::DevHmLock:
    case Id::DevHmLockDefault:
        return Error::NoHmPresent;
    case Id::DevTriggerMode:
    case Id::DevTriggerCondition:
    case Id::ModIoOptions:
    case Id::ModIoVoltage:
    case Id::ModAinRange:
    case Id::ModDin:
    case Id::ModDout:
    case Id::ModAout: {
        if (!config_.io_module)
            return Error::NoIomPresent;
        if (p.id == Id::DevTriggerMode || p.id == Id::DevTriggerCondition) {
            out = std::to_string(p.id == Id::DevTriggerMode ? trigger_mode_ : trigger_condition_);
            return std::nullopt;
        }
        const auto& io = io_[static_cast<std::size_t>(indices[0])];
        const std::int64_t v = p.id == Id::ModIoOptions ? io.options
                               : p.id == Id::ModIoVoltage ? io.voltage
                               : p.id == Id::ModAinRange ? io.ain_range
                               : p.id == Id::ModDout ? io.dout
                               : p.id == Id::ModAout ? io.aout[static_cast<std::size_t>(indices[1])]
                                                     : 0;   // GP-DIN: nothing is wired to the inputs
        out = std::to_string(v);
        return std::nullopt;
    }
    case Id::ModPower:
        out = module_power_[static_cast<std::size_t>(indices[0])] ? "1" : "0";
        return std::nullopt;
    case Id::ModState:
        out = std::to_string(module_state(static_cast<std::size_t>(indices[0])));
        return std::nullopt;
    case Id::ModuleStateAlias:
        out = std::to_string(module_state(0));
        return std::nullopt;
    case Id::ModChannels: {
        const auto m = static_cast<std::size_t>(indices[0]);
        out = std::to_string(std::min<std::size_t>(3, channels_.size() - 3 * m));
        return std::nullopt;
    }
    case Id::ModTemperature:
        out = std::to_string(config_.channels[3 * static_cast<std::size_t>(indices[0])].temperature_c);
        return std::nullopt;
    default:
        break;
    }
    if (p.scope == Scope::Channel)
        return read_channel(p, static_cast<std::size_t>(indices[0]), out);
    if (p.kind == Kind::Stored) {
        out = number(p, device_store_[static_cast<std::size_t>(p.id)]);
        return std::nullopt;
    }
    return Error::InvalidParameter;
}

std::int64_t* Controller::setting(Channel& ch, Id id)
{
    auto& s = ch.settings();
    switch (id) {
    case Id::ControlOptions:
        return &s.control_options;
    case Id::MaxFrequency:
        return &s.max_frequency;
    case Id::StepFrequency:
        return &s.step_frequency;
    case Id::StepAmplitude:
        return &s.step_amplitude;
    case Id::ScanVelocity:
        return &s.scan_velocity;
    case Id::ReferencingOptions:
        return &s.referencing_options;
    case Id::SafeDirection:
        return &s.safe_direction;
    case Id::RangeMin:
        return &s.range_min;
    case Id::RangeMax:
        return &s.range_max;
    default:
        return nullptr;
    }
}

std::int64_t& Controller::stored_channel(std::size_t channel, Id id)
{
    return channel_store_[channel][static_cast<std::size_t>(id)];
}

std::optional<Error> Controller::read_channel(const Property& p, std::size_t index, std::string& out)
{
    Channel& ch = *channels_[index];
    const auto put = [&](std::int64_t v) {
        out = number(p, v);
        return std::nullopt;
    };
    if (p.id >= Id::TunMovementType && p.id <= Id::TunTargetHold) {
        const auto i = static_cast<std::size_t>(p.id) - kTuningFirst;
        if (p.id == Id::TunCustom)
            return put((ch.type_code() >= 250 && ch.type_code() <= 253) || ch.type_code() == 0 ? 1 : 0);
        return put(ch.tuning()[i]);
    }
    switch (p.id) {
    case Id::Amplifier:
        return put(ch.amplifier() ? 1 : 0);
    case Id::ActuatorMode:
        return put(ch.actuator_mode());
    case Id::LoopInput:
        return put(ch.loop_input());
    case Id::SensorInputSelect:
        return put(stored_channel(index, Id::SensorInputSelect));
    case Id::SensorValue: {
        std::int64_t v = 0;
        if (const auto e = ch.sensor_value(v))
            return e;
        return put(v);
    }
    case Id::AuxValue:
        // The aux input: the I/O module's analog input or the sensor module's (Aux Input Select,
        // 4.11.3); nothing is wired to either: 0.
        if (!config_.io_module && stored_channel(index, Id::AuxInputSelect) == 0)
            return Error::NoIomPresent;
        return put(0);
    case Id::AuxInputValue:
        if (!config_.io_module)
            return Error::NoIomPresent;
        return put(0);
    case Id::TriggerMode:
        if (!config_.io_module)
            return Error::NoIomPresent;
        return put(stored_channel(index, Id::TriggerMode));
    case Id::PositionerType:
        return put(ch.type_code());
    case Id::PositionerTypeName:
        out = quote_string(ch.type_name());
        return std::nullopt;
    case Id::AuxPositionerTypeName:
        out = quote_string("CUSTOM" + std::to_string(stored_channel(index, Id::AuxPositionerType) - 250));
        return std::nullopt;
    case Id::State:
        return put(channel_state(index));
    case Id::Position:
        if (ch.sensor_failed())
            return Error::NoSensorPresent;
        return put(ch.position());
    case Id::TargetPosition:
        return put(ch.target());
    case Id::ScanPosition:
        return put(ch.scan_position());
    case Id::FollowingError:
        return put(ch.moving() ? ch.target() - ch.position() : 0);
    case Id::HoldTime:
        return put(ch.settings().hold_ms);
    case Id::Velocity:
        return put(ch.settings().velocity);
    case Id::Acceleration:
        return put(ch.settings().acceleration);
    case Id::SensorPowerMode:
    case Id::SensorModeAlias:
        return put(static_cast<std::int64_t>(ch.sensor_power()));
    case Id::SensorDelayAlias:
        return put(stored_channel(index, Id::PowerSaveDelay));
    case Id::ScaleOffset:
        return put(ch.scale_offset());
    case Id::ScaleInversion:
        return put(ch.scale_inverted() ? 1 : 0);
    case Id::CalibrationOptions:
        return put(ch.settings().calibration_options);
    case Id::CorrectionOptions:
        return put(stored_channel(index, Id::CorrectionOptions) | 0x05);   // bits 0 and 2 read 1
    case Id::DistanceToMark:
        return put(ch.distance_to_mark());
    case Id::ChannelError:
        return put(ch.take_error());   // "reset to 0 (NONE) by reading it" (4.10.1)
    case Id::ChannelTemperature:
        return put(ch.config().temperature_c);
    case Id::TunWriteProtection:
        return put(ch.write_protected() ? 1 : 0);
    default:
        break;
    }
    if (auto* field = setting(ch, p.id))
        return put(*field);
    if (p.kind == Kind::Stored)
        return put(stored_channel(index, p.id));
    return Error::InvalidParameter;
}

std::optional<Error> Controller::write(const Property& p, const std::vector<std::int64_t>& indices, const Command& c,
                                       SessionState& s, Result& r)
{
    const std::int64_t v = c.params.empty() ? 0 : c.params[0].integer;
    const bool numeric = p.type == Type::I32 || p.type == Type::I64;
    // Hold Time takes -1 for SA_CTL_INFINITE (errata); every other value is checked against its range.
    if (numeric && p.id != Id::StrFrame && p.id != Id::Move && (v < p.min || v > p.max) && p.access != Access::Tuning)
        return Error::InvalidParameter;
    switch (p.id) {
    case Id::Cls:
        s.errors.clear();   // "clears all status data structures"
        return std::nullopt;
    case Id::Ese:
        s.ese = v;
        return std::nullopt;
    case Id::Sre:
        s.sre = v;
        return std::nullopt;
    case Id::Opc:
    case Id::Wai:
        return std::nullopt;   // "no effect" (Table 6.1)
    case Id::Rst:
        power_up();   // "resets the device (reconnect necessary!)"
        r.reset = true;
        return std::nullopt;
    case Id::CgrOpen:
        if (group_owner_ || !group_.empty())
            return Error::InvalidConfiguration;   // "only one command group can be open at a time" (2.14)
        if (group_armed_)
            return Error::InvalidConfiguration;
        if (v == 1) {   // the external trigger: the I/O module's input, in mode CMD_GROUP (2.14, 2.17)
            if (!config_.io_module)
                return Error::NoIomPresent;
            if (trigger_mode_ != 3)
                return Error::InvalidInputTrigMode;
        }
        group_owner_ = &s;
        group_.clear();
        group_finished_ = false;
        group_values_.clear();
        group_external_ = v == 1;
        return std::nullopt;
    case Id::CgrClose:
        if (group_owner_ != &s)
            return Error::InvalidConfiguration;
        close_group(s);
        return std::nullopt;
    case Id::CgrAbort:
        if (group_owner_ != &s && group_armed_ != &s)
            return Error::InvalidConfiguration;
        group_owner_ = nullptr;
        group_armed_ = nullptr;
        group_.clear();
        return std::nullopt;
    case Id::StrOpen:
        return stream_open(v, s);
    case Id::StrFrame:
        return stream_frame(c);
    case Id::StrClose:
        return stream_close();
    case Id::StrAbort:
        if (!stream_.open)
            return Error::InvalidStreamHandle;
        stream_abort(Error::Aborted);
        return std::nullopt;
    case Id::DevName: {
        const auto& name = c.params[0].text;
        if (name.empty() || name.size() > 63)
            return Error::InvalidParameter;
        device_name_ = name;
        return std::nullopt;
    }
    case Id::DevEstopMode:
        estop_mode_ = v;   // writing any valid value also releases a locked device (2.17.2)
        set_locked(false);
        return std::nullopt;
    case Id::DevHmLock:
    case Id::DevHmLockDefault:
        return Error::NoHmPresent;
    case Id::DevTriggerMode:
    case Id::DevTriggerCondition:
    case Id::ModIoOptions:
    case Id::ModIoVoltage:
    case Id::ModAinRange:
    case Id::ModDout:
    case Id::ModDoutSet:
    case Id::ModDoutClear:
    case Id::ModAout: {
        if (!config_.io_module)
            return Error::NoIomPresent;
        if (p.id == Id::DevTriggerMode) {
            trigger_mode_ = v;
            return std::nullopt;
        }
        if (p.id == Id::DevTriggerCondition) {
            trigger_condition_ = v;
            return std::nullopt;
        }
        auto& io = io_[static_cast<std::size_t>(indices[0])];
        switch (p.id) {
        case Id::ModIoOptions:
            io.options = v;
            break;
        case Id::ModIoVoltage:
            io.voltage = v;
            break;
        case Id::ModAinRange:
            io.ain_range = v;
            break;
        case Id::ModDout:
            io.dout = v;
            break;
        case Id::ModDoutSet:
            io.dout |= v;   // the given bits only (4.11.8)
            break;
        case Id::ModDoutClear:
            io.dout &= ~v;
            break;
        default:
            io.aout[static_cast<std::size_t>(indices[1])] = v;
            break;
        }
        return std::nullopt;
    }
    case Id::ModPower: {
        const auto m = static_cast<std::size_t>(indices[0]);
        for (std::size_t i = 3 * m; i < std::min(channels_.size(), 3 * m + 3); ++i)
            if (channels_[i]->streaming())
                return Error::BusyStreaming;
        module_power_[m] = v != 0;
        for (std::size_t i = 3 * m; i < std::min(channels_.size(), 3 * m + 3); ++i)
            channels_[i]->set_power_supply(v != 0);
        return std::nullopt;
    }
    default:
        break;
    }
    if (p.scope == Scope::Command) {
        auto& ch = *channels_[static_cast<std::size_t>(indices[0])];
        const auto i = static_cast<std::size_t>(indices[0]);
        started_by_[i] = &s;
        switch (p.id) {
        case Id::Move:
            return ch.move(static_cast<MoveMode>(stored_channel(i, Id::MoveMode)), v);
        case Id::Stop:
            if (ch.streaming())
                return Error::BusyStreaming;
            ch.stop();
            return std::nullopt;
        case Id::Calibrate:
            return ch.calibrate();
        case Id::Reference:
            return ch.reference();
        default:
            return std::nullopt;
        }
    }
    if (p.scope == Scope::Channel) {
        const auto i = static_cast<std::size_t>(indices[0]);
        if (channels_[i]->streaming())   // "unavailable for movement or configuration commands" (2.15.1)
            return Error::BusyStreaming;
        if (const auto e = write_channel(p, *channels_[i], v))
            return e;
        if (p.id == Id::TriggerMode) {
            // Position compare with its limits the wrong way round (4.14.1).
            if (v == 1 && stored_channel(i, Id::CompareLimitMax) < stored_channel(i, Id::CompareLimitMin))
                return Error::InvalidConfiguration;
            stored_channel(i, Id::TriggerMode) = v;
            return std::nullopt;
        }
        if (auto* field = setting(*channels_[i], p.id))
            *field = v;
        else if (p.kind == Kind::Stored)
            stored_channel(i, p.id) = v;
        else if (p.id == Id::SensorDelayAlias)
            stored_channel(i, Id::PowerSaveDelay) = v;
        else if (p.id == Id::CorrectionOptions)
            stored_channel(i, Id::CorrectionOptions) = v;
        else if (p.id == Id::SensorInputSelect)
            stored_channel(i, Id::SensorInputSelect) = v;
        return std::nullopt;
    }
    if (p.kind == Kind::Stored) {
        device_store_[static_cast<std::size_t>(p.id)] = v;
        return std::nullopt;
    }
    return Error::InvalidParameter;
}

std::optional<Error> Controller::write_channel(const Property& p, Channel& ch, std::int64_t v)
{
    if (p.access == Access::Tuning) {
        const auto i = static_cast<std::size_t>(p.id) - kTuningFirst;
        if (ch.write_protected())
            return Error::PermissionDenied;
        if (v < p.min || v > p.max)
            return Error::InvalidParameter;
        return ch.set_tuning(i, v);
    }
    switch (p.id) {
    case Id::Amplifier:
        ch.set_amplifier(v != 0);
        return std::nullopt;
    case Id::ActuatorMode:
        return ch.set_actuator_mode(v);
    case Id::LoopInput:
        if (v == 2)   // AUX_IN: the aux input as feedback is not modelled (an I/O module's unit has it)
            return config_.io_module ? Error::FeatureNotSupported : Error::NoIomPresent;
        return ch.set_loop_input(v);
    case Id::SensorInputSelect:
        return v == 1 && ch.type().sensor != 'P' ? std::optional<Error>(Error::InvalidParameter) : std::nullopt;
    case Id::PositionerType:
        return ch.set_type(v);
    case Id::Position:
        return ch.set_position(v);
    case Id::HoldTime:
        return ch.set_hold_time(v);
    case Id::Velocity:
        return ch.set_velocity(v);
    case Id::Acceleration:
        return ch.set_acceleration(v);
    case Id::SensorPowerMode:
    case Id::SensorModeAlias:
        return ch.set_sensor_power(v);
    case Id::ScaleOffset:
        ch.set_scale_offset(v);
        return std::nullopt;
    case Id::ScaleInversion:
        ch.set_scale_inverted(v != 0);
        return std::nullopt;
    case Id::CalibrationOptions:
        if (v & ~0x107LL)
            return Error::InvalidParameter;   // bits 3-7 and 9-31 are reserved (4.6.1)
        ch.settings().calibration_options = v;
        return std::nullopt;
    case Id::CorrectionOptions:
        if (v & 0x10)
            return Error::PermissionDenied;   // advanced sensor correction: a feature permission (2.19)
        return std::nullopt;
    case Id::TriggerMode:
        if (!config_.io_module)
            return Error::NoIomPresent;   // "no I/O module -> NO_IOM_PRESENT" (4.14.1)
        return std::nullopt;
    case Id::TunSave:
        return ch.save_tuning(v);
    case Id::TunWriteProtection:
        ch.set_write_protection(v);
        return std::nullopt;
    case Id::MoveMode:
    case Id::ControlOptions:
    case Id::MaxFrequency:
    case Id::StepFrequency:
    case Id::StepAmplitude:
    case Id::ScanVelocity:
    case Id::ReferencingOptions:
    case Id::SafeDirection:
    case Id::RangeMin:
    case Id::RangeMax:
        if (ch.moving() && (p.id == Id::MoveMode || p.id == Id::SafeDirection))
            return Error::BusyMoving;
        return std::nullopt;
    default:
        return std::nullopt;
    }
}

void Controller::close_group(SessionState& s)
{
    group_owner_ = nullptr;
    if (group_external_) {   // armed: the input trigger runs it (6.4.1)
        group_armed_ = &s;
        return;
    }
    run_group(s);   // direct trigger: every command of the group now, in order
}

void Controller::run_group(SessionState& s)
{
    std::vector<std::string> values;
    Result r;
    auto grouped = std::move(group_);
    group_.clear();
    group_armed_ = nullptr;
    for (const auto& g : grouped)
        run(*g.property, g.indices, g.command, s, values, r);
    group_values_ = std::move(values);
    group_finished_ = true;
}

void Controller::set_locked(bool locked)
{
    locked_ = locked;
    for (auto& ch : channels_)
        ch->set_locked(locked);
}

void Controller::emergency_stop()
{
    if (stream_.open)
        stream_abort(Error::Aborted);
    group_owner_ = nullptr;
    group_armed_ = nullptr;
    group_.clear();
    for (auto& ch : channels_) {
        ch->stop();   // a hard stop, also under acceleration control: the second stop (2.6.5)
        if (ch->moving())
            ch->stop();
    }
    if (estop_mode_ == 1 || estop_mode_ == 2)   // RESTRICTED, AUTO_RELEASE: locked (2.17.2)
        set_locked(true);
}

void Controller::set_trigger_input(bool high)
{
    if (high == input_high_)
        return;
    input_high_ = high;
    const bool active = trigger_condition_ == 0 ? high : !high;   // RISING or FALLING (4.13.2)
    if (!active) {
        // AUTO_RELEASE: the lock ends when the trigger line is released (the inverse edge).
        if (trigger_mode_ == 1 && locked_ && estop_mode_ == 2)
            set_locked(false);
        return;
    }
    switch (trigger_mode_) {
    case 1:
        emergency_stop();
        break;
    case 2:   // a stream armed for its trigger starts; later edges are ignored (EXTERNAL_ONCE)
        if (stream_.open && stream_.mode != 0 && stream_.ready && !stream_.running)
            stream_start(clock_.now());
        break;
    case 3:
        if (group_armed_)
            run_group(*group_armed_);
        break;
    default:   // DISABLED; EVENT notifies the SmarActCTL library, which the ASCII interface has not
        break;
    }
}

void Controller::broadcast_stop(std::size_t from)
{
    for (std::size_t i = 0; i < channels_.size(); ++i)
        if (i != from && channels_[i]->moving())
            channels_[i]->stop();
}

Ticks Controller::next_change(Ticks now) const
{
    Ticks next = kNever;
    for (const auto& c : channels_)
        next = std::min(next, c->next_change(now));
    if (stream_.running)
        next = std::min(next, std::max(frame_tick(stream_.next), now + 1));
    return next;
}

void Controller::tick(Ticks now)
{
    for (std::size_t i = 0; i < channels_.size(); ++i) {
        auto& c = *channels_[i];
        c.tick(now);
        // Broadcast stop (10.9): a channel that met an end stop stops the others (bit 0).
        if (c.take_end_stop_event() &&
            (channel_store_[i][static_cast<std::size_t>(Id::BroadcastStop)] & 0x01))
            broadcast_stop(i);
        if (c.take_code_inversion_detected())
            stored_channel(i, Id::DistanceCodeInverted) = 0;
    }
    if (stream_.running)
        stream_tick(now);
}

// ---- trajectory streaming (2.15, 6.5) ----

std::optional<Error> Controller::stream_open(std::int64_t mode, const SessionState& s)
{
    if (stream_.open)
        return Error::BusyStreaming;   // one stream at a time (2.15)
    if (mode != 0) {   // external triggers come through the I/O module's input in mode STREAM (2.17)
        if (!config_.io_module)
            return Error::NoIomPresent;
        if (trigger_mode_ != 2)
            return Error::InvalidInputTrigMode;
    }
    stream_ = Stream{};
    stream_.mode = mode;
    stream_.open = true;
    stream_.owner = &s;
    stream_.rate = device_store_[static_cast<std::size_t>(Id::DevStreamBaseRate)];
    stream_.interpolate = (device_store_[static_cast<std::size_t>(Id::DevStreamOptions)] & 0x01) == 0;
    return std::nullopt;
}

std::optional<Error> Controller::stream_frame(const Command& c)
{
    if (!stream_.open || stream_.closed)
        return Error::InvalidStreamHandle;
    if (c.params.size() % 2 != 0)
        return Error::InvalidArraySize;
    std::vector<std::size_t> chans;
    std::vector<std::int64_t> positions;
    for (std::size_t i = 0; i < c.params.size(); i += 2) {
        const auto ch = c.params[i].integer;
        const auto pos = c.params[i + 1].integer;
        if (ch < 0 || static_cast<std::size_t>(ch) >= channels_.size())
            return Error::InvalidChannelIndex;
        if (std::find(chans.begin(), chans.end(), static_cast<std::size_t>(ch)) != chans.end())
            return Error::InvalidParameter;
        if (pos < -100'000'000'000'000 || pos > 100'000'000'000'000)
            return Error::InvalidParameter;
        chans.push_back(static_cast<std::size_t>(ch));
        positions.push_back(pos);
    }
    if (stream_.total == 0) {
        // The first frame names the channels (2.15.1); each must be able to move closed-loop with
        // its sensor on (not in power save).
        for (const auto ch : chans) {
            auto& channel = *channels_[ch];
            if (const auto e = channel.movement_refused(true))
                return e;
            if (channel.sensor_power() == SensorPower::PowerSave)
                return Error::InvalidSensorMode;
            if (channel.moving())
                return Error::BusyMoving;
        }
        stream_.channels = chans;
        for (const auto ch : chans) {
            channels_[ch]->stop();
            channels_[ch]->set_streaming(true);
        }
    } else if (chans != stream_.channels) {
        return Error::InvalidParameter;   // every frame: the same channels in the same order
    }
    std::size_t used = positions.size();
    for (const auto& f : stream_.frames)
        used += f.size();
    if (used > kStreamBuffer)
        return Error::BufferOverflow;
    stream_.frames.push_back(std::move(positions));
    ++stream_.total;
    // Direct mode starts once the buffer is half full ("stream ready", 2.15.1); an external one
    // is armed then, and starts at its trigger.
    if (!stream_.running && used * 2 >= kStreamBuffer) {
        if (stream_.mode == 0)
            stream_start(clock_.now());
        else
            stream_.ready = true;
    }
    return std::nullopt;
}

std::optional<Error> Controller::stream_close()
{
    if (!stream_.open || stream_.closed)
        return Error::InvalidStreamHandle;
    stream_.closed = true;
    if (!stream_.running) {
        if (stream_.total < 2) {   // "a stream must consist of at least two frames"
            stream_abort(Error::InsufficientFrames);
            return Error::InsufficientFrames;
        }
        if (stream_.mode == 0)
            stream_start(clock_.now());   // a short stream is ready when closed
        else
            stream_.ready = true;
    }
    return std::nullopt;
}

void Controller::stream_abort(Error e)
{
    for (const auto ch : stream_.channels)
        channels_[ch]->stream_failed(e);
    stream_ = Stream{};
}

Ticks Controller::frame_tick(std::int64_t k) const
{
    // Frame k runs k base periods after the start; tick-exact for rates that divide the tick rate.
    return stream_.start + (k * static_cast<std::int64_t>(clock_.tick_hz()) + stream_.rate - 1) / stream_.rate;
}

void Controller::stream_start(Ticks now)
{
    stream_.running = true;
    stream_.start = now;
    stream_.next = 0;
    stream_tick(now);
}

void Controller::stream_tick(Ticks now)
{
    while (stream_.running && frame_tick(stream_.next) <= now) {
        if (stream_.frames.empty()) {
            if (stream_.closed) {   // every frame ran: the stream is finished, the channels rest at its end
                for (const auto ch : stream_.channels)
                    channels_[ch]->set_streaming(false);
                stream_ = Stream{};
            } else {   // not closed and nothing left: a buffer underflow ends it (2.15.1)
                stream_abort(Error::BufferUnderflow);
            }
            return;
        }
        const auto frame = std::move(stream_.frames.front());
        stream_.frames.pop_front();
        const Ticks duration = frame_tick(stream_.next + 1) - frame_tick(stream_.next);
        for (std::size_t i = 0; i < frame.size(); ++i)
            channels_[stream_.channels[i]]->stream_to(static_cast<double>(frame[i]), duration, stream_.interpolate);
        ++stream_.next;
    }
}

} // namespace rigsim::mcs2
