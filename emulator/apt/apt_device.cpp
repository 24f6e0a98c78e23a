#include "emulator/apt/apt_device.hpp"

#include "emulator/apt/messages.hpp"
#include "emulator/apt/wire.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>

namespace rigsim::apt {

namespace {

/// The only channel of a single-unit controller: P_MOD_CHAN1.
constexpr std::uint16_t kChan1 = 0x01;

std::string chan_and_i32(std::int32_t v)
{
    std::string d;
    put_u16(d, kChan1);
    put_i32(d, v);
    return d;
}

std::string velocity_block(const VelocityParams& v)
{
    std::string d;
    put_i32(d, v.min);
    put_i32(d, v.acceleration);
    put_i32(d, v.max);
    return d;
}

enum class Field { U16, I16, U32, I32 };

/// One field of a SET's data packet and the values the manual allows for it.
struct FieldRange {
    std::uint16_t set_id;
    std::string_view name;
    std::size_t offset;   ///< in the data packet (the channel word is at 0)
    Field type;
    std::int64_t min;
    std::int64_t max;
};

constexpr std::int64_t kMaxLong = 2'147'483'647;

/// The field ranges of every SET a motor unit acts on, as the manual's data structures give
/// them (page in the comment). Fields the manual gives no range (positions, distances, the
/// backlash: signed longs) take any value. Rules that tie two fields together, and modes
/// whose values are not a range, are checked in handle_bay().
constexpr FieldRange kSetRanges[] = {
    // p. 30: acceleration and maximum velocity are unsigned longs; a zero would never move.
    {MGMSG_MOT_SET_VELPARAMS, "minimum velocity", 2, Field::I32, 0, kMaxLong},
    {MGMSG_MOT_SET_VELPARAMS, "acceleration", 6, Field::I32, 1, kMaxLong},
    {MGMSG_MOT_SET_VELPARAMS, "maximum velocity", 10, Field::I32, 1, kMaxLong},
    // p. 32: jog mode 1 continuous, 2 single step; stop mode 1 immediate, 2 profiled.
    {MGMSG_MOT_SET_JOGPARAMS, "jog mode", 2, Field::U16, 1, 2},
    {MGMSG_MOT_SET_JOGPARAMS, "jog step size", 4, Field::I32, 0, kMaxLong},
    {MGMSG_MOT_SET_JOGPARAMS, "jog minimum velocity", 8, Field::I32, 0, kMaxLong},
    {MGMSG_MOT_SET_JOGPARAMS, "jog acceleration", 12, Field::I32, 1, kMaxLong},
    {MGMSG_MOT_SET_JOGPARAMS, "jog maximum velocity", 16, Field::I32, 1, kMaxLong},
    {MGMSG_MOT_SET_JOGPARAMS, "stop mode", 20, Field::U16, 1, 2},
    // p. 51: proportional, integral, differential and integral limit 0..32767.
    {MGMSG_MOT_SET_DCPIDPARAMS, "proportional", 2, Field::I32, 0, 32767},
    {MGMSG_MOT_SET_DCPIDPARAMS, "integral", 6, Field::I32, 0, 32767},
    {MGMSG_MOT_SET_DCPIDPARAMS, "differential", 10, Field::I32, 0, 32767},
    {MGMSG_MOT_SET_DCPIDPARAMS, "integral limit", 14, Field::I32, 0, 32767},
    // p. 58: mode 1 jog, 2 go to position.
    {MGMSG_MOT_SET_BUTTONPARAMS, "mode", 2, Field::U16, 1, 2},
    // p. 61: PMDPOSITIONLOOPPARAMS. The PosErrLim text says "0 to 7FFFFFF" (seven Fs); the
    // dword's other limit field, Integral Limit, says 7FFFFFFF: taken for both.
    {MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, "Kp", 2, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, "Ki", 4, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, "integral limit", 6, Field::U32, 0, kMaxLong},
    {MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, "Kd", 10, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, "KdTimePos", 12, Field::U16, 1, 32767},
    {MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, "KvffPos", 16, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, "KaffPos", 18, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, "PosErrLim", 20, Field::U32, 0, kMaxLong},
    // p. 63-64: MotorBias "-32767 to 32768" in a signed word: -32767..32767.
    {MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, "ContCurrentLim", 2, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, "EnergyLim", 4, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, "MotorLim", 6, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, "MotorBias", 8, Field::I16, -32767, 32767},
    // p. 66: settle time 0..32767 cycles; both windows 0..65535 (any word).
    {MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS, "settle time", 2, Field::U16, 0, 32767},
    // p. 69: mode 0 trapezoidal, 2 S-curve (1 is no mode); jerk 0..4294967295 (any dword).
    {MGMSG_MOT_SET_PMDPROFILEMODEPARAMS, "mode", 2, Field::U16, 0, 2},
    // p. 71 and 73: phase 0 A, 1 B, 2 A and B; gains, limit, dead band, feed-forward 0..32767.
    {MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, "phase", 2, Field::U16, 0, 2},
    {MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, "KpCurrent", 4, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, "KiCurrent", 6, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, "ILimCurrent", 8, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, "IDeadBand", 10, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, "Kff", 12, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, "phase", 2, Field::U16, 0, 2},
    {MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, "KpSettled", 4, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, "KiSettled", 6, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, "ILimSettled", 8, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, "IDeadBandSettled", 10, Field::U16, 0, 32767},
    {MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, "KffSettled", 12, Field::U16, 0, 32767},
};

std::int64_t field_value(std::string_view data, const FieldRange& r)
{
    switch (r.type) {
    case Field::U16:
        return get_u16(data, r.offset);
    case Field::I16:
        return get_i16(data, r.offset);
    case Field::U32:
        return get_u32(data, r.offset);
    case Field::I32:
        return get_i32(data, r.offset);
    }
    return 0;
}

/// The first field of SET `f` outside its range in kSetRanges, as "<name> <value> (<min>..<max>)".
std::optional<std::string> out_of_range(const Frame& f)
{
    for (const auto& r : kSetRanges) {
        if (r.set_id != f.id)
            continue;
        const auto v = field_value(f.data, r);
        if (v < r.min || v > r.max)
            return std::string(r.name) + " " + std::to_string(v) + " (" + std::to_string(r.min) + ".."
                   + std::to_string(r.max) + ")";
    }
    return std::nullopt;
}

} // namespace

/// One connection: its own framer; frames go to the device, answers come back.
class AptSession : public Session {
public:
    AptSession(AptDevice& device, SendFn send, std::string peer, spdlog::logger& log)
        : device_(device), send_(std::move(send)), peer_(std::move(peer)), log_(log)
    {
        device_.attach(this);
    }
    ~AptSession() override { device_.detach(this); }

    void receive(std::string_view bytes) override
    {
        const Ticks now = device_.clock().now();
        if (framer_.buffered() > 0
            && now - last_byte_ > device_.clock().ticks_from_ms(AptDevice::kInterByteTimeout_ms)) {
            const auto n = framer_.discard_partial();
            log_.warn("{}: dropped {} byte(s) of an unfinished APT message after {} ms without its rest", peer_, n,
                      AptDevice::kInterByteTimeout_ms);
        }
        if (!bytes.empty())
            last_byte_ = now;
        std::size_t dropped = 0;
        while (!bytes.empty()) {
            const auto r = framer_.parse(bytes);
            bytes.remove_prefix(r.consumed);
            dropped += r.dropped;
            if (r.status != FrameFramer::Status::Frame)
                continue;
            std::string reply;
            device_.handle(r.frame, peer_, reply);
            if (!reply.empty())
                send_(reply);   // one frame, one write
        }
        if (dropped > 0)
            log_.warn("{}: skipped {} byte(s) that start no valid APT message", peer_, dropped);
        device_.flush();
    }

    void send(std::string_view frame) { send_(frame); }

private:
    AptDevice& device_;
    SendFn send_;
    std::string peer_;
    spdlog::logger& log_;
    FrameFramer framer_;
    Ticks last_byte_ = 0;   ///< clock tick of the last bytes received
};

AptDevice::AptDevice(const DeviceConfig& config, models::World& world, std::shared_ptr<spdlog::logger> log,
                     StateStore* store)
    : config_(config), clock_(world.clock()), log_(std::move(log)), model_(*find_controller(config.model)),
      serial_(config.apt.serial_number != 0 ? config.apt.serial_number : model_.serial_prefix * 1'000'000 + 1),
      store_(store)
{
    if (model_.rack)
        for (const auto& stage : config.apt.bays)
            channels_.push_back(std::make_unique<MotorChannel>(model_, *find_stage(stage), clock_));
    else
        channels_.push_back(std::make_unique<MotorChannel>(model_, *find_stage(config.apt.stage), clock_));
    last_move_.assign(channels_.size(), 0);
    restore_from_eeprom();
    clock_.add(this);
}

namespace {

/// The parameter SETs MOT_SET_EEPROMPARAMS saves (p. 60: "the message containing the
/// parameters to be saved"): the motor chapter's settings that rigsim's controllers act on.
/// Not SET_POSCOUNTER or SET_ENCCOUNTER: the 'live' counts (p. 28), unknown at power-up.
constexpr std::uint16_t kEepromSets[] = {
    MGMSG_MOT_SET_VELPARAMS, MGMSG_MOT_SET_JOGPARAMS, MGMSG_MOT_SET_GENMOVEPARAMS, MGMSG_MOT_SET_MOVERELPARAMS,
    MGMSG_MOT_SET_MOVEABSPARAMS, MGMSG_MOT_SET_HOMEPARAMS, MGMSG_MOT_SET_LIMSWITCHPARAMS, MGMSG_MOT_SET_DCPIDPARAMS,
    MGMSG_MOT_SET_AVMODES, MGMSG_MOT_SET_POTPARAMS, MGMSG_MOT_SET_BUTTONPARAMS,
    MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS,
    MGMSG_MOT_SET_PMDPROFILEMODEPARAMS, MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS,
    MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, MGMSG_MOT_SET_PMDSTAGEAXISPARAMS};

bool saved_by_eeprom(std::uint16_t id)
{
    return std::find(std::begin(kEepromSets), std::end(kEepromSets), id) != std::end(kEepromSets);
}

/// The manual's name of message `id`, or its number if the table does not know it.
std::string message_name(std::uint16_t id)
{
    if (const auto* info = find_message(id))
        return std::string(info->name);
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%04x", id);
    return buf;
}

/// State file key of a saved SET message: "bay0/0x0413".
std::string eeprom_key(std::size_t bay, std::uint16_t id)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string k = "bay" + std::to_string(bay) + "/0x";
    for (int shift = 12; shift >= 0; shift -= 4)
        k += kHex[(id >> shift) & 0xf];
    return k;
}

/// The bay and message of a key exactly as eeprom_key writes it, or nullopt.
std::optional<std::pair<std::size_t, std::uint16_t>> parse_eeprom_key(const std::string& key)
{
    constexpr std::size_t kMaxBayDigits = 3;
    if (key.compare(0, 3, "bay") != 0)
        return std::nullopt;
    std::size_t i = 3;
    std::size_t bay = 0;
    while (i < key.size() && i - 3 < kMaxBayDigits && key[i] >= '0' && key[i] <= '9')
        bay = bay * 10 + static_cast<std::size_t>(key[i++] - '0');
    if (i == 3 || key.compare(i, 3, "/0x") != 0 || key.size() != i + 7)
        return std::nullopt;
    unsigned id = 0;
    for (i += 3; i < key.size(); ++i) {
        const char c = key[i];
        if (c >= '0' && c <= '9')
            id = id * 16 + static_cast<unsigned>(c - '0');
        else if (c >= 'a' && c <= 'f')
            id = id * 16 + static_cast<unsigned>(c - 'a' + 10);
        else
            return std::nullopt;
    }
    const auto parsed = std::make_pair(bay, static_cast<std::uint16_t>(id));
    if (eeprom_key(parsed.first, parsed.second) != key)   // "bay00/...": one spelling per entry
        return std::nullopt;
    return parsed;
}

std::string to_hex(std::string_view data)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (unsigned char c : data) {
        out += kHex[c >> 4];
        out += kHex[c & 0xf];
    }
    return out;
}

/// `hex` (an even number of [0-9a-fA-F]) as bytes in `out`, or false and why not in `why`.
bool from_hex(const std::string& hex, std::string& out, std::string& why)
{
    auto digit = [](char c) {
        if (c >= '0' && c <= '9')
            return c - '0';
        if (c >= 'a' && c <= 'f')
            return c - 'a' + 10;
        if (c >= 'A' && c <= 'F')
            return c - 'A' + 10;
        return -1;
    };
    for (std::size_t i = 0; i < hex.size(); ++i) {
        if (digit(hex[i]) < 0) {
            why = "data is not hex (character " + std::to_string(i + 1) + " is '" + printable(hex.substr(i, 1)) + "')";
            return false;
        }
    }
    if (hex.size() % 2 != 0) {
        why = "data has an odd number of hex digits (" + std::to_string(hex.size()) + ")";
        return false;
    }
    out.clear();
    for (std::size_t i = 0; i < hex.size(); i += 2)
        out.push_back(static_cast<char>(digit(hex[i]) * 16 + digit(hex[i + 1])));
    return true;
}

} // namespace

void AptDevice::save_to_eeprom(std::size_t bay, std::uint16_t id, std::string_view peer)
{
    if (!saved_by_eeprom(id)) {
        log_->warn("{}: MOT_SET_EEPROMPARAMS for 0x{:04x} ({}): not a parameter SET it saves, nothing saved", peer, id,
                   message_name(id));
        return;
    }
    const auto it = last_set_.find({bay, id});
    if (it == last_set_.end()) {
        log_->warn("{}: MOT_SET_EEPROMPARAMS for 0x{:04x}: no such parameters were set, nothing saved", peer, id);
        return;
    }
    if (!store_) {
        log_->info("{}: MOT_SET_EEPROMPARAMS for 0x{:04x}: kept until the daemon exits (no --state-file)", peer, id);
        return;
    }
    // Saved as the parameters of the bay's channel, whatever channel word the SET carried.
    std::string data;
    put_u16(data, kChan1);
    data += it->second.substr(2);
    store_->set(config_.name, eeprom_key(bay, id), to_hex(data));
    log_->info("{}: MOT_SET_EEPROMPARAMS for 0x{:04x}: saved", peer, id);
}

std::string AptDevice::stage_axis_block(std::size_t bay) const
{
    // p. 75: stage ID word (MLS203 X 0x10, Y 0x11; 0 for stages the manual does not list), axis ID word, part number char[16],
    // serial dword, counts per unit dword, min/max position long, max acceleration,
    // deceleration and velocity long, reserved to 72 bytes after the channel word.
    const auto& stage = channels_[bay]->stage();
    std::string d;
    put_u16(d, stage.pmd_stage_id);
    put_u16(d, 0);
    std::string part(stage.pmd_part_number.empty() ? stage.name : stage.pmd_part_number);
    part.resize(16, '\0');
    d += part;
    put_u32(d, serial_ % 1'000'000 * 10 + static_cast<std::uint32_t>(bay));
    put_u32(d, static_cast<std::uint32_t>(stage.counts_per_mm));
    put_i32(d, channels_[bay]->min_position());
    put_i32(d, channels_[bay]->max_position());
    // "inherent in the design of the stage and cannot be altered" (p. 75): not VELPARAMS.
    const auto& design = channels_[bay]->design_velocity();
    const auto max_acceleration = stage.pmd_max_acceleration > 0 ? stage.pmd_max_acceleration : design.acceleration;
    put_i32(d, max_acceleration);
    put_i32(d, max_acceleration);
    put_i32(d, stage.pmd_max_velocity > 0 ? stage.pmd_max_velocity : design.max);
    d.resize(72, '\0');
    return d;
}

bool AptDevice::handle_pmd(std::size_t bay, const Frame& f, std::string& reply)
{
    static constexpr std::uint16_t kSets[] = {
        MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS, MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS, MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS,
        MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS, MGMSG_MOT_SET_PMDPROFILEMODEPARAMS,
        MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, MGMSG_MOT_SET_PMDSTAGEAXISPARAMS};
    // Each trio is SET, REQ = SET + 1, GET = SET + 2.
    for (const auto set : kSets) {
        if (f.id == set) {
            if (set == MGMSG_MOT_SET_PMDSTAGEAXISPARAMS) {
                // "can only be used to increase the Minimum position value and decrease the
                // Maximum position value": the travel narrows, nothing else changes.
                // Data: chan, stage ID, axis ID, part number[16], serial, counts per unit,
                // MinPos at 30, MaxPos at 34 (p. 75).
                const auto min_position = get_i32(f.data, 30), max_position = get_i32(f.data, 34);
                auto& ch = *channels_[bay];
                if (min_position >= max_position || min_position < ch.min_position() || max_position > ch.max_position()) {
                    forget_set();
                    log_->warn("MOT_SET_PMDSTAGEAXISPARAMS travel {}..{} is not within {}..{}: ignored", min_position,
                               max_position, ch.min_position(), ch.max_position());
                    return true;
                }
                ch.narrow_travel(min_position, max_position);
                return true;
            }
            if (set == MGMSG_MOT_SET_PMDPROFILEMODEPARAMS) {
                // p. 69: mode 0 trapezoidal, 2 S-curve; jerk in PMD jerk units (7.1).
                const auto mode = get_u16(f.data, 2);
                if (mode != 0 && mode != 2) {
                    forget_set();
                    log_->warn("MOT_SET_PMDPROFILEMODEPARAMS mode {} (0 trapezoidal, 2 S-curve): ignored", mode);
                    return true;
                }
                channels_[bay]->profile_mode = mode;
                channels_[bay]->jerk = get_u32(f.data, 4);
            }
            pmd_blocks_[{bay, set}] = std::string(f.data.substr(2));
            return true;
        }
        if (f.id == set + 1) {
            const auto* get = find_message(static_cast<std::uint16_t>(set + 2));
            std::string d;
            put_u16(d, kChan1);
            if (set == MGMSG_MOT_SET_PMDSTAGEAXISPARAMS) {
                d += stage_axis_block(bay);
            } else {
                const auto it = pmd_blocks_.find({bay, set});
                std::string block = it != pmd_blocks_.end() ? it->second : std::string();
                block.resize(static_cast<std::size_t>(get->data_length) - 2, '\0');
                d += block;
            }
            reply += encode_with_data(get->id, host_, address_of(bay), d);
            return true;
        }
    }
    return false;
}

void AptDevice::restore_from_eeprom()
{
    if (!store_)
        return;
    // What this device's non-volatile memory can hold: a parameter SET that MOT_SET_EEPROMPARAMS
    // saves, of one of its bays, as long as the table says, for the bay's channel, and accepted
    // by the bay as if a client had sent it. Returns why an entry is none of that.
    auto restore = [&](const std::string& key, const nlohmann::json& value) -> std::optional<std::string> {
        const auto parsed = parse_eeprom_key(key);
        if (!parsed)
            return "the key is not bay<N>/0x<4 lower-case hex digits>";
        const auto [bay, id] = *parsed;
        if (bay >= channels_.size())
            return "no bay " + std::to_string(bay) + " (the " + config_.model
                   + (channels_.size() == 1 ? " has bay 0 only)" : " has bays 0 to " + std::to_string(channels_.size() - 1) + ")");
        if (!saved_by_eeprom(id))
            return message_name(id) + " is not a parameter SET that MOT_SET_EEPROMPARAMS saves";
        if (!value.is_string())
            return std::string("expected a string of hex digits, got ") + value.type_name();
        std::string data;
        std::string why;
        if (!from_hex(value.get<std::string>(), data, why))
            return why;
        const auto* info = find_message(id);
        if (data.size() != static_cast<std::size_t>(info->data_length))
            return std::to_string(data.size()) + " data bytes, " + std::string(info->name) + " has "
                   + std::to_string(info->data_length);
        if (get_u16(data, 0) != kChan1)
            return "channel " + std::to_string(get_u16(data, 0)) + " in the data; bay " + std::to_string(bay)
                   + " is channel 1";
        Frame f;
        f.id = id;
        f.dest = address_of(bay);
        f.source = kHost;
        f.has_data = true;
        f.data = data;
        f.info = info;
        last_set_.erase({bay, id});
        std::string ignored;
        handle_bay(bay, f, "state file", ignored);
        const auto accepted = last_set_.find({bay, id});
        if (accepted == last_set_.end() || accepted->second != data)
            return "the bay ignores this " + std::string(info->name) + " (its warning says why)";
        log_->info("restored {} of bay {} from the state file", info->name, bay);
        return std::nullopt;
    };
    // A copy: reject() drops the entry from the store.
    const nlohmann::json entries = store_->device_state(config_.name);
    for (const auto& [key, value] : entries.items())
        if (const auto why = restore(key, value))
            store_->reject(config_.name, key, *why);
}

std::uint8_t AptDevice::address_of(std::size_t bay) const
{
    return model_.rack ? static_cast<std::uint8_t>(kBay0 + bay) : kGenericUsb;
}

AptDevice::~AptDevice()
{
    clock_.remove(this);
}

std::unique_ptr<Session> AptDevice::open_session(SendFn send, std::string peer)
{
    return std::make_unique<AptSession>(*this, std::move(send), std::move(peer), *log_);
}

void AptDevice::detach(AptSession* s)
{
    sessions_.erase(std::remove(sessions_.begin(), sessions_.end(), s), sessions_.end());
}

std::string AptDevice::info_packet(std::optional<std::size_t> bay) const
{
    // HW_GET_INFO: serial long, model char[8], type word, firmware byte[4] (minor, interim,
    // major, unused), notes char[64], number of channels word: 84 bytes (manual p. 21).
    // In a rack, the motherboard (type 45) reports its bays; each bay's card (type 44 for a
    // brushless card) reports one channel and a serial with the card prefix.
    std::string d;
    const bool card = model_.rack && bay;
    put_u32(d, card ? model_.bay_serial_prefix * 1'000'000 + (serial_ % 1'000'000) * 10 % 1'000'000 + static_cast<std::uint32_t>(*bay)
                    : serial_);
    std::string model(config_.model.substr(0, 8));
    model.resize(8, '\0');
    d += model;
    put_u16(d, card ? model_.bay_hw_type : model_.hw_type);
    d += std::string{'\x03', '\x00', '\x01', '\x00'};   // firmware 1.0.3
    std::string notes(model_.notes);
    notes.resize(64, '\0');
    d += notes;
    put_u16(d, static_cast<std::uint16_t>(model_.rack && !bay ? built_in_bays() : 1));
    return d;
}

std::string AptDevice::status_packet(std::size_t bay) const
{
    const auto& ch = *channels_[bay];
    std::string d;
    put_u16(d, kChan1);
    put_i32(d, ch.position());
    put_i32(d, ch.encoder());
    put_u32(d, ch.status_bits());
    return d;
}

std::string AptDevice::dc_status_packet(std::size_t bay) const
{
    const auto& ch = *channels_[bay];
    std::string d;
    put_u16(d, kChan1);
    put_i32(d, ch.position());
    put_i16(d, ch.velocity_word());
    put_u16(d, 0);   // reserved
    put_u32(d, ch.status_bits());
    return d;
}

void AptDevice::start_updates()
{
    updates_ = true;
    updates_since_ack_ = 0;
    next_update_ = clock_.now() + clock_.ticks_from_ms(kUpdatePeriod_ms);
}

void AptDevice::handle(const Frame& f, std::string_view peer, std::string& reply)
{
    host_ = f.source;
    if (!model_.rack) {
        // A single unit answers as 0x50 and, as the real cubes do, also acts on messages
        // that clients address to the motherboard (0x11) or bay 0 (0x21).
        if (f.dest != kGenericUsb && f.dest != kRack && f.dest != kBay0) {
            log_->warn("{}: {} to 0x{:02x}: no such module, ignored", peer, f.info->name, f.dest);
            return;
        }
        return handle_bay(0, f, peer, reply);
    }
    if (f.dest == kRack)
        return handle_motherboard(f, peer, reply);
    if (f.dest >= kBay0 && f.dest < kBay0 + channels_.size())
        return handle_bay(f.dest - kBay0, f, peer, reply);
    if (f.dest >= kBay0 && f.dest < kBay0 + built_in_bays())
        return handle_empty_bay(f.dest - kBay0, f, peer, reply);
    log_->warn("{}: {} to 0x{:02x}: no module in that bay, ignored", peer, f.info->name, f.dest);
}

void AptDevice::handle_motherboard(const Frame& f, std::string_view peer, std::string& reply)
{
    auto answer_header = [&](std::uint16_t id, std::uint8_t p1, std::uint8_t p2) {
        reply += encode_header_only(id, p1, p2, host_, kRack);
    };
    switch (f.id) {
    case MGMSG_HW_REQ_INFO:
        reply += encode_with_data(MGMSG_HW_GET_INFO, host_, kRack, info_packet(std::nullopt));
        return;
    case MGMSG_RACK_REQ_BAYUSED:
        // p. 23: "Is controller bay #1 (i.e. bay 0) occupied": bays are numbered from 0 here.
        // The BBD203's and BSC203's channel cards are built in: every bay is occupied, with a
        // stage or not (a card without one reports its motor not connected).
        return answer_header(MGMSG_RACK_GET_BAYUSED, f.param1, f.param1 < built_in_bays() ? 0x01 : 0x02);
    case MGMSG_RACK_REQ_STATUSBITS: {
        std::string d;
        put_u32(d, 0);   // digital inputs of the USER IO connector: all low
        reply += encode_with_data(MGMSG_RACK_GET_STATUSBITS, host_, kRack, d);
        return;
    }
    case MGMSG_RACK_SET_DIGOUTPUTS:
    case MGMSG_RACK_REQ_DIGOUTPUTS: {
        // p. 26: header only; param1 the outputs (bits 0..3 for outputs 1..4), param2 the bay
        // whose card the outputs belong to ("28, 02, 01, 22, 11, 01": bay address 0x22), or 0
        // for the motherboard's own.
        const bool bay_ok = f.param2 == 0 || (f.param2 >= kBay0 && f.param2 < kBay0 + channels_.size());
        if (!bay_ok || (f.id == MGMSG_RACK_SET_DIGOUTPUTS && f.param1 > 0x0F)) {
            log_->warn("{}: {} for outputs 0x{:02x} of bay 0x{:02x} (outputs 0..0x0f; 0 or a present bay): ignored",
                       peer, f.info->name, f.param1, f.param2);
            return;
        }
        if (f.id == MGMSG_RACK_SET_DIGOUTPUTS) {
            digital_outputs_[f.param2] = f.param1;
            return;
        }
        return answer_header(MGMSG_RACK_GET_DIGOUTPUTS, digital_outputs_[f.param2], f.param2);
    }
    default:
        if (!handle_system(f, peer))
            log_->warn("{}: {} to the motherboard: it acts on no such message, ignored", peer, f.info->name);
        return;
    }
}

std::size_t AptDevice::built_in_bays() const
{
    return std::max(channels_.size(), static_cast<std::size_t>(model_.max_bays));
}

void AptDevice::handle_empty_bay(std::size_t bay, const Frame& f, std::string_view peer, std::string& reply)
{
    const std::uint8_t me = address_of(bay);
    if (handle_system(f, peer))
        return;
    if (f.id == MGMSG_HW_REQ_INFO) {
        reply += encode_with_data(MGMSG_HW_GET_INFO, host_, me, info_packet(bay));
        return;
    }
    const std::uint16_t chan = f.has_data ? get_u16(f.data, 0) : f.param1;
    if (chan == kChan1) {
        // The card answers what it knows without a motor: its info, and status with the
        // "motor connected" bit (0x100, p.77) clear.
        std::string status;
        put_u16(status, kChan1);
        switch (f.id) {
        case MGMSG_MOT_REQ_STATUSBITS:
            put_u32(status, 0);
            reply += encode_with_data(MGMSG_MOT_GET_STATUSBITS, host_, me, status);
            return;
        case MGMSG_MOT_REQ_STATUSUPDATE:
            put_i32(status, 0);
            put_i32(status, 0);
            put_u32(status, 0);
            reply += encode_with_data(MGMSG_MOT_GET_STATUSUPDATE, host_, me, status);
            return;
        case MGMSG_MOT_REQ_DCSTATUSUPDATE:
            if (model_.motor == MotorKind::Stepper)
                break;
            put_i32(status, 0);
            put_u32(status, 0);
            put_u32(status, 0);
            reply += encode_with_data(MGMSG_MOT_GET_DCSTATUSUPDATE, host_, me, status);
            return;
        default:
            break;
        }
    }
    log_->warn("{}: {} to bay {} (0x{:02x}): no stage is connected to it, ignored", peer, f.info->name, bay, me);
}

bool AptDevice::handle_system(const Frame& f, std::string_view peer)
{
    switch (f.id) {
    case MGMSG_MOD_IDENTIFY:
        ++identify_count_;   // the front panel LED flashes: counted (identify_count()) and logged
        log_->info("{}: MOD_IDENTIFY: front panel flashes", peer);
        return true;
    case MGMSG_HW_DISCONNECT:
        log_->info("{}: HW_DISCONNECT", peer);
        return true;
    case MGMSG_HW_START_UPDATEMSGS:
        start_updates();
        return true;
    case MGMSG_HW_STOP_UPDATEMSGS:
        updates_ = false;
        next_update_ = kNever;
        return true;
    case MGMSG_HW_YES_FLASH_PROGRAMMING:
    case MGMSG_HW_NO_FLASH_PROGRAMMING:
        return true;   // later protocol issues: accepted silently, as the real units do
    case MGMSG_MOT_SUSPEND_ENDOFMOVEMSGS:   // p. 82-83: header only, params 0: the whole unit
        end_of_move_messages_ = false;
        return true;
    case MGMSG_MOT_RESUME_ENDOFMOVEMSGS:
        end_of_move_messages_ = true;
        return true;
    case MGMSG_MOT_ACK_DCSTATUSUPDATE:
        updates_since_ack_ = 0;   // "server alive" (p. 80): no channel, params 0
        if (updates_ && next_update_ <= clock_.now())   // resume the 100 ms rhythm from now
            next_update_ = clock_.now() + clock_.ticks_from_ms(kUpdatePeriod_ms);
        return true;
    default:
        return false;
    }
}

void AptDevice::handle_bay(std::size_t bay, const Frame& f, std::string_view peer, std::string& reply)
{
    auto& ch = *channels_[bay];
    const std::uint8_t me = address_of(bay);
    // What MOT_SET_EEPROMPARAMS can save: the last SET the bay accepted (forget_set() undoes
    // this for one it ignores).
    set_undo_.reset();
    if (f.has_data && f.info->name.find("_SET_") != std::string_view::npos) {
        const auto it = last_set_.find({bay, f.id});
        set_undo_ = SetUndo{{bay, f.id}, it != last_set_.end() ? std::optional<std::string>(it->second) : std::nullopt};
        last_set_[{bay, f.id}] = std::string(f.data);
    }
    auto answer = [&](std::uint16_t id, const std::string& data) { reply += encode_with_data(id, host_, me, data); };
    auto answer_header = [&](std::uint16_t id, std::uint8_t p1, std::uint8_t p2) {
        reply += encode_header_only(id, p1, p2, host_, me);
    };
    // Channel addressing: header-only messages carry it in param1, others as the first word.
    const std::uint16_t sent_chan = f.has_data ? get_u16(f.data, 0) : f.param1;
    // The manual says the channel must be 1, but T-Cube and K-Cube firmware takes channel 0
    // as its one channel too (public drivers send 0 and work); rack bays keep the manual's rule.
    const std::uint16_t chan = !model_.rack && sent_chan == 0 ? kChan1 : sent_chan;
    auto wrong_channel = [&] {
        forget_set();
        log_->warn("{}: {} for channel {}: a module has only channel 1, ignored", peer, f.info->name, sent_chan);
    };
    if (handle_system(f, peer))
        return;
    switch (f.id) {
    // ---- generic ----
    case MGMSG_MOD_SET_CHANENABLESTATE:
        if (chan != kChan1 || (f.param2 != 1 && f.param2 != 2))
            return wrong_channel();
        ch.set_enabled(f.param2 == 1);
        return;
    case MGMSG_MOD_REQ_CHANENABLESTATE:
        if (chan != kChan1)
            return wrong_channel();
        return answer_header(MGMSG_MOD_GET_CHANENABLESTATE, kChan1, ch.enabled() ? 1 : 2);
    case MGMSG_HW_REQ_INFO:
        return answer(MGMSG_HW_GET_INFO, info_packet(model_.rack ? std::optional<std::size_t>(bay) : std::nullopt));
    case MGMSG_HUB_REQ_BAYUSED:
        if (model_.rack)
            break;   // a hub question for a cube
        // p. 24: -0x01 (0xFF) means a standalone T-/K-Cube, off any hub.
        return answer_header(MGMSG_HUB_GET_BAYUSED, 0xFF, 0);
    default:
        break;
    }
    if (chan != kChan1)
        return wrong_channel();
    if (f.has_data) {
        if (auto bad = out_of_range(f)) {
            forget_set();
            log_->warn("{}: {} with {}: ignored", peer, f.info->name, *bad);
            return;
        }
    }
    switch (f.id) {
    // ---- motor parameters: SET stores, REQ answers GET ----
    case MGMSG_MOT_SET_POSCOUNTER:
        ch.set_position(get_i32(f.data, 2));
        return;
    case MGMSG_MOT_REQ_POSCOUNTER:
        return answer(MGMSG_MOT_GET_POSCOUNTER, chan_and_i32(ch.position()));
    case MGMSG_MOT_SET_ENCCOUNTER:
        ch.set_encoder(get_i32(f.data, 2));
        return;
    case MGMSG_MOT_REQ_ENCCOUNTER:
        return answer(MGMSG_MOT_GET_ENCCOUNTER, chan_and_i32(ch.encoder()));
    case MGMSG_MOT_SET_VELPARAMS: {
        const VelocityParams v{get_i32(f.data, 2), get_i32(f.data, 6), get_i32(f.data, 10)};
        if (v.min > v.max) {   // p. 30: the minimum (start) velocity of a ramp up to the maximum
            forget_set();
            log_->warn("{}: MOT_SET_VELPARAMS with minimum velocity {} above the maximum {}: ignored", peer, v.min,
                       v.max);
            return;
        }
        ch.velocity = v;
        return;
    }
    case MGMSG_MOT_REQ_VELPARAMS: {
        std::string d;
        put_u16(d, kChan1);
        return answer(MGMSG_MOT_GET_VELPARAMS, d + velocity_block(ch.velocity));
    }
    case MGMSG_MOT_SET_JOGPARAMS: {
        JogParams j;
        j.mode = get_u16(f.data, 2);
        j.step_size = get_i32(f.data, 4);
        j.velocity = {get_i32(f.data, 8), get_i32(f.data, 12), get_i32(f.data, 16)};
        j.stop_mode = get_u16(f.data, 20);
        if (j.velocity.min > j.velocity.max) {
            forget_set();
            log_->warn("{}: MOT_SET_JOGPARAMS with jog minimum velocity {} above the maximum {}: ignored", peer,
                       j.velocity.min, j.velocity.max);
            return;
        }
        ch.jog = j;
        return;
    }
    case MGMSG_MOT_REQ_JOGPARAMS: {
        const auto& j = ch.jog;
        std::string d;
        put_u16(d, kChan1);
        put_u16(d, j.mode);
        put_i32(d, j.step_size);
        d += velocity_block(j.velocity);
        put_u16(d, j.stop_mode);
        return answer(MGMSG_MOT_GET_JOGPARAMS, d);
    }
    case MGMSG_MOT_SET_GENMOVEPARAMS:
        ch.backlash = get_i32(f.data, 2);
        return;
    case MGMSG_MOT_REQ_GENMOVEPARAMS:
        return answer(MGMSG_MOT_GET_GENMOVEPARAMS, chan_and_i32(ch.backlash));
    case MGMSG_MOT_SET_MOVERELPARAMS:
        ch.relative_distance = get_i32(f.data, 2);
        return;
    case MGMSG_MOT_REQ_MOVERELPARAMS:
        return answer(MGMSG_MOT_GET_MOVERELPARAMS, chan_and_i32(ch.relative_distance));
    case MGMSG_MOT_SET_MOVEABSPARAMS:
        ch.absolute_position = get_i32(f.data, 2);
        return;
    case MGMSG_MOT_REQ_MOVEABSPARAMS:
        return answer(MGMSG_MOT_GET_MOVEABSPARAMS, chan_and_i32(ch.absolute_position));
    case MGMSG_MOT_SET_HOMEPARAMS: {
        HomeParams h{get_u16(f.data, 2), get_u16(f.data, 4), get_i32(f.data, 6), get_i32(f.data, 10)};
        // p. 37: on a brushless (MLS203) channel only the homing velocity counts; the other
        // fields are kept as sent and ignored.
        const bool only_velocity = model_.motor == MotorKind::Brushless;
        if (h.velocity <= 0
            || (!only_velocity
                && ((h.direction != 1 && h.direction != 2) || (h.limit_switch != 1 && h.limit_switch != 4) || h.offset < 0))) {
            forget_set();
            log_->warn("{}: MOT_SET_HOMEPARAMS out of range: ignored", peer);
            return;
        }
        ch.home_params = h;
        return;
    }
    case MGMSG_MOT_REQ_HOMEPARAMS: {
        const auto& h = ch.home_params;
        std::string d;
        put_u16(d, kChan1);
        put_u16(d, h.direction);
        put_u16(d, h.limit_switch);
        put_i32(d, h.velocity);
        put_i32(d, h.offset);
        return answer(MGMSG_MOT_GET_HOMEPARAMS, d);
    }
    case MGMSG_MOT_SET_LIMSWITCHPARAMS: {
        LimitSwitchParams l{get_u16(f.data, 2), get_u16(f.data, 4), get_i32(f.data, 6), get_i32(f.data, 10),
                            get_u16(f.data, 14)};
        // p. 39: hardware modes 1..6 and software modes 1..3, each possibly with 0x80.
        const auto hard_ok = [](std::uint16_t m) { return (m & ~0x80u) >= 1 && (m & ~0x80u) <= 6; };
        const auto soft = l.mode & ~0x80u;
        if (!hard_ok(l.cw_hard) || !hard_ok(l.ccw_hard) || soft < 1 || soft > 3) {
            forget_set();
            log_->warn("{}: MOT_SET_LIMSWITCHPARAMS modes {}, {} (1..6) and {} (1..3): ignored", peer, l.cw_hard,
                       l.ccw_hard, l.mode);
            return;
        }
        ch.limit_switch = l;
        return;
    }
    case MGMSG_MOT_REQ_LIMSWITCHPARAMS: {
        const auto& l = ch.limit_switch;
        std::string d;
        put_u16(d, kChan1);
        put_u16(d, l.cw_hard);
        put_u16(d, l.ccw_hard);
        put_i32(d, l.cw_soft);
        put_i32(d, l.ccw_soft);
        put_u16(d, l.mode);
        return answer(MGMSG_MOT_GET_LIMSWITCHPARAMS, d);
    }
    case MGMSG_MOT_SET_DCPIDPARAMS:
        if (model_.motor == MotorKind::Stepper)
            break;
        ch.pid_params.assign(f.data.substr(2));
        return;
    case MGMSG_MOT_REQ_DCPIDPARAMS:
        if (model_.motor == MotorKind::Stepper)
            break;
        if (ch.pid_params.empty())
            ch.pid_params = std::string("\x8c\x01\x00\x00\x0e\x01\x00\x00\xa0\x0f\x00\x00\xfc\x12\x00\x00\x0f\x00", 18);
        return answer(MGMSG_MOT_GET_DCPIDPARAMS, std::string("\x01\x00", 2) + ch.pid_params);
    case MGMSG_MOT_SET_AVMODES:
        // p. 52-53: mode bits 1 (ident), 2 (limit switch), 8 (moving); no others.
        if ((get_u16(f.data, 2) & ~0x000Bu) != 0) {
            forget_set();
            log_->warn("{}: MOT_SET_AVMODES mode bits 0x{:04x} (bits of 0x000b only): ignored", peer, get_u16(f.data, 2));
            return;
        }
        ch.av_modes.assign(f.data.substr(2));
        return;
    case MGMSG_MOT_REQ_AVMODES:
        if (ch.av_modes.empty())
            ch.av_modes = std::string("\x0b\x00", 2);   // LED: ident, limit switch, moving
        return answer(MGMSG_MOT_GET_AVMODES, std::string("\x01\x00", 2) + ch.av_modes);
    case MGMSG_MOT_SET_POTPARAMS: {
        // p. 55-57: windows in ADC counts up to 127, each from the previous one on, and "Wnd3
        // must be greater than Wnd2"; velocities in encoder counts/s.
        const auto zero = get_u16(f.data, 2), w1 = get_u16(f.data, 8), w2 = get_u16(f.data, 14), w3 = get_u16(f.data, 20);
        const bool velocities_ok = get_i32(f.data, 4) >= 0 && get_i32(f.data, 10) >= 0 && get_i32(f.data, 16) >= 0
                                   && get_i32(f.data, 22) >= 0;
        if (!(zero <= w1 && w1 <= w2 && w2 < w3 && w3 <= 127) || !velocities_ok) {
            forget_set();
            log_->warn("{}: MOT_SET_POTPARAMS windows {}, {}, {}, {} (rising to 127) or a negative velocity: ignored",
                       peer, zero, w1, w2, w3);
            return;
        }
        ch.pot_params.assign(f.data.substr(2));
        return;
    }
    case MGMSG_MOT_REQ_POTPARAMS:
        if (ch.pot_params.empty())
            ch.pot_params.assign(24, '\0');
        return answer(MGMSG_MOT_GET_POTPARAMS, std::string("\x01\x00", 2) + ch.pot_params);
    case MGMSG_MOT_SET_BUTTONPARAMS:
        ch.button_params.assign(f.data.substr(2));
        return;
    case MGMSG_MOT_REQ_BUTTONPARAMS:
        if (ch.button_params.empty())
            ch.button_params.assign(14, '\0');
        return answer(MGMSG_MOT_GET_BUTTONPARAMS, std::string("\x01\x00", 2) + ch.button_params);
    case MGMSG_MOT_SET_EEPROMPARAMS:
        return save_to_eeprom(bay, get_u16(f.data, 2), peer);
    // ---- moves ----
    case MGMSG_MOT_MOVE_HOME:
    case MGMSG_MOT_MOVE_RELATIVE:
    case MGMSG_MOT_MOVE_ABSOLUTE:
    case MGMSG_MOT_MOVE_JOG:
    case MGMSG_MOT_MOVE_VELOCITY:
        if (!ch.enabled()) {
            log_->warn("{}: {} while channel 1 is disabled: it does not move", peer, f.info->name);
            return;
        }
        // Drivers re-send MOVE_HOME every 0.5-3 s while they wait for MOVE_HOMED: a unit
        // that is homing keeps homing rather than starting over.
        if (f.id == MGMSG_MOT_MOVE_HOME && ch.homing()) {
            log_->info("{}: MOT_MOVE_HOME while homing: homing goes on", peer);
            return;
        }
        break;
    default:
        break;
    }
    switch (f.id) {
    case MGMSG_MOT_MOVE_HOME:
    case MGMSG_MOT_MOVE_RELATIVE:
    case MGMSG_MOT_MOVE_ABSOLUTE:
    case MGMSG_MOT_MOVE_JOG:
    case MGMSG_MOT_MOVE_VELOCITY:
        last_move_[bay] = f.id;
        break;
    default:
        break;
    }
    switch (f.id) {
    case MGMSG_MOT_MOVE_HOME:
        ch.home();
        return;
    case MGMSG_MOT_MOVE_RELATIVE:
        ch.move_relative(f.has_data ? get_i32(f.data, 2) : ch.relative_distance);
        return;
    case MGMSG_MOT_MOVE_ABSOLUTE:
        ch.move_absolute(f.has_data ? get_i32(f.data, 2) : ch.absolute_position);
        return;
    case MGMSG_MOT_MOVE_JOG:
        if (f.param2 != 1 && f.param2 != 2)
            return log_->warn("{}: MOT_MOVE_JOG direction {}: ignored", peer, f.param2);
        ch.jog_move(f.param2 == 1);
        return;
    case MGMSG_MOT_MOVE_VELOCITY:
        if (f.param2 != 1 && f.param2 != 2)
            return log_->warn("{}: MOT_MOVE_VELOCITY direction {}: ignored", peer, f.param2);
        ch.move_velocity(f.param2 == 1);
        return;
    case MGMSG_MOT_MOVE_STOP:
        ch.stop(f.param2 == 1);
        return;
    // ---- status ----
    case MGMSG_MOT_REQ_STATUSUPDATE:
        return answer(MGMSG_MOT_GET_STATUSUPDATE, status_packet(bay));
    case MGMSG_MOT_REQ_DCSTATUSUPDATE:
        if (model_.motor == MotorKind::Stepper) {   // a DC message: a stepper controller ignores it
            forget_set();
            log_->warn("{}: {} is not a message a {} acts on: ignored", peer, f.info->name, config_.model);
            return;
        }
        return answer(MGMSG_MOT_GET_DCSTATUSUPDATE, dc_status_packet(bay));
    case MGMSG_MOT_REQ_STATUSBITS: {
        std::string d;
        put_u16(d, kChan1);
        put_u32(d, ch.status_bits());
        return answer(MGMSG_MOT_GET_STATUSBITS, d);
    }
    default:
        if (model_.motor == MotorKind::Brushless && handle_pmd(bay, f, reply))
            return;
        // A message of the table that this controller does not act on (a GET sent by a
        // host, a rack or brushless message): the real unit ignores it.
        forget_set();
        log_->warn("{}: {} is not a message a {} acts on: ignored", peer, f.info->name, config_.model);
        return;
    }
}

void AptDevice::forget_set()
{
    if (!set_undo_)
        return;
    if (set_undo_->previous)
        last_set_[set_undo_->key] = *set_undo_->previous;
    else
        last_set_.erase(set_undo_->key);
    set_undo_.reset();
}

void AptDevice::broadcast(const std::string& frame)
{
    for (auto* s : sessions_)
        s->send(frame);
}

std::string AptDevice::fault_report(std::size_t bay) const
{
    // The only fault rigsim models: the motor stalled against an end stop (a move past an
    // ignored limit switch), which trips its current limit (DC servo: status bit 0x01000000)
    // or the position error limit (brushless: motion error, bit 0x00004000).
    if (model_.rich_fault_reports) {
        // Later protocol issues: MsgIdent word (what caused it), Code word, Notes char[64].
        std::string d;
        put_u16(d, last_move_[bay]);
        put_u16(d, kFaultCodeStalled);
        std::string notes = "Motor stalled at the end of travel: current limit reached";
        notes.resize(64, '\0');
        d += notes;
        return encode_with_data(MGMSG_HW_RICHRESPONSE, host_, address_of(bay), d);
    }
    // p. 19: header only; in a card-slot system the motherboard sends it ("TX 80, 00, 00, 00, 01, 11").
    return encode_header_only(MGMSG_HW_RESPONSE, 0, 0, host_, model_.rack ? kRack : address_of(bay));
}

void AptDevice::flush()
{
    for (std::size_t bay = 0; bay < channels_.size(); ++bay) {
        const std::uint8_t me = address_of(bay);
        for (const auto event : channels_[bay]->take_events()) {
            if (!end_of_move_messages_)
                continue;
            // USB "server alive" (p. 80): end-of-move messages count as status update type
            // messages too, while update messages are on.
            if (updates_ && updates_since_ack_ >= kUpdatesWithoutAck)
                continue;
            if (updates_)
                ++updates_since_ack_;
            // MOVE_COMPLETED/STOPPED carry MOTSTATUS (steppers) or MOTDCSTATUS (p. 44).
            const auto status = model_.motor == MotorKind::Stepper ? status_packet(bay) : dc_status_packet(bay);
            switch (event) {
            case MotorEvent::MoveCompleted:
                broadcast(encode_with_data(MGMSG_MOT_MOVE_COMPLETED, host_, me, status));
                break;
            case MotorEvent::Stopped:
                broadcast(encode_with_data(MGMSG_MOT_MOVE_STOPPED, host_, me, status));
                break;
            case MotorEvent::Homed:
                broadcast(encode_header_only(MGMSG_MOT_MOVE_HOMED, kChan1, 0, host_, me));
                break;
            case MotorEvent::Fault:
                broadcast(fault_report(bay));
                break;
            }
        }
    }
}

Ticks AptDevice::next_change(Ticks now) const
{
    Ticks next = updates_ && updates_since_ack_ < kUpdatesWithoutAck ? std::max(next_update_, now + 1) : kNever;
    for (const auto& ch : channels_)
        next = std::min(next, ch->next_change(now));
    return next;
}

void AptDevice::tick(Ticks now)
{
    for (auto& ch : channels_)
        ch->tick(now);
    flush();
    if (updates_ && now >= next_update_) {
        next_update_ += clock_.ticks_from_ms(kUpdatePeriod_ms);
        // USB units stop after 50 updates that the host did not acknowledge (MOT_ACK_DCSTATUSUPDATE).
        if (updates_since_ack_ < kUpdatesWithoutAck) {
            ++updates_since_ack_;
            for (std::size_t bay = 0; bay < channels_.size(); ++bay)
                broadcast(model_.motor == MotorKind::Stepper
                              ? encode_with_data(MGMSG_MOT_GET_STATUSUPDATE, host_, address_of(bay), status_packet(bay))
                              : encode_with_data(MGMSG_MOT_GET_DCSTATUSUPDATE, host_, address_of(bay), dc_status_packet(bay)));
        }
    }
}

} // namespace rigsim::apt
