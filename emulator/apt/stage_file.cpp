#include "emulator/apt/stage_file.hpp"

#include "emulator/core/config_reader.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <string_view>

namespace rigsim::apt {
namespace {

using nlohmann::json;

/// The position counters are 32-bit (MOT_GET_POSCOUNTER, p. 44): a travel must fit them.
constexpr double kMaxCounterCounts = 2'147'483'647.0;
/// A rotation stage's axis spans ±2^30 counts (motor_channel.cpp): many turns at this resolution.
constexpr double kMaxRotaryCountsPerDeg = 1'000'000.0;
/// Names are shown in the control API and (cut to 16 characters) in PMDSTAGEAXISPARAMS.
constexpr std::size_t kMaxNameLength = 64;
/// MOT_GET_PMDSTAGEAXISPARAMS PartNoAxis: 16 characters (p. 75).
constexpr std::size_t kMaxPartNumberLength = 16;

/// Every key a stage object may hold; which ones a stage has depends on its kind and motor.
constexpr std::array<std::string_view, 26> kStageKeys{
    "name",
    "about",
    "kind",
    "motor",
    "travel_mm",
    "angle_range_deg",
    "counts_per_mm",
    "counts_per_deg",
    "max_velocity_mm_s",
    "max_velocity_deg_s",
    "acceleration_mm_s2",
    "acceleration_deg_s2",
    "home_velocity_mm_s",
    "home_velocity_deg_s",
    "home_offset_mm",
    "home_offset_deg",
    "apt_velocity_per_mm_s",
    "apt_velocity_per_deg_s",
    "apt_acceleration_per_mm_s2",
    "apt_acceleration_per_deg_s2",
    "limit_switches",
    "home_direction",
    "pmd_stage_id",
    "pmd_part_number",
    "pmd_max_velocity",
    "pmd_max_acceleration",
};

/// A key of a linear stage (mm) and its counterpart on a rotary stage or goniometer (degrees).
struct UnitKey {
    std::string_view mm;
    std::string_view deg;
};

constexpr UnitKey kCounts{"counts_per_mm", "counts_per_deg"};
constexpr UnitKey kMaxVelocity{"max_velocity_mm_s", "max_velocity_deg_s"};
constexpr UnitKey kAcceleration{"acceleration_mm_s2", "acceleration_deg_s2"};
constexpr UnitKey kHomeVelocity{"home_velocity_mm_s", "home_velocity_deg_s"};
constexpr UnitKey kHomeOffset{"home_offset_mm", "home_offset_deg"};
constexpr UnitKey kAptVelocity{"apt_velocity_per_mm_s", "apt_velocity_per_deg_s"};
constexpr UnitKey kAptAcceleration{"apt_acceleration_per_mm_s2", "apt_acceleration_per_deg_s2"};
constexpr std::array<UnitKey, 7> kUnitKeys{kCounts,       kMaxVelocity, kAcceleration,   kHomeVelocity,
                                           kHomeOffset,   kAptVelocity, kAptAcceleration};

constexpr std::array<std::string_view, 4> kPmdKeys{"pmd_stage_id", "pmd_part_number", "pmd_max_velocity",
                                                   "pmd_max_acceleration"};

template <typename T>
struct Choice {
    std::string_view name;
    T value;
};

constexpr std::array<Choice<StageKind>, 3> kKinds{
    {{"linear", StageKind::Linear}, {"rotary", StageKind::Rotary}, {"goniometer", StageKind::Goniometer}}};
constexpr std::array<Choice<MotorKind>, 3> kMotors{
    {{"dc_servo", MotorKind::DcServo}, {"stepper", MotorKind::Stepper}, {"brushless", MotorKind::Brushless}}};
constexpr std::array<Choice<LimitSwitches>, 4> kSwitches{{{"both", LimitSwitches::Both},
                                                          {"forward", LimitSwitches::Forward},
                                                          {"reverse", LimitSwitches::Reverse},
                                                          {"none", LimitSwitches::None}}};
constexpr std::array<Choice<bool>, 2> kHomeDirections{{{"reverse", false}, {"forward", true}}};

/// `x` as the messages show numbers: 50, 2.4, 1919.6418.
std::string number_text(double x)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.15g", x);
    return buf;
}

/// The keys of one stage object, read in the order of docs/config.md's table.
class StageReader {
public:
    StageReader(const ConfigReader& r, const json& object, const std::string& pointer)
        : r_(r), object_(object), pointer_(pointer) {}

    const json* find(std::string_view key) const { return ConfigReader::find(object_, key); }
    std::string at(std::string_view key) const { return pointer_to(pointer_, key); }
    [[noreturn]] void fail(std::string_view key, const std::string& what) const { r_.fail(at(key), what); }

    /// One of `choices` (a string), or a type error listing them.
    template <typename T, std::size_t N>
    T choice(std::string_view key, const json& v, const std::array<Choice<T>, N>& choices) const
    {
        if (v.is_string())
            for (const auto& c : choices)
                if (v.get_ref<const std::string&>() == c.name)
                    return c.value;
        std::string list;
        for (std::size_t i = 0; i < N; ++i)
            list += std::string(i == 0 ? "" : i + 1 == N ? " or " : ", ") + "\"" + std::string(choices[i].name) + "\"";
        fail(key, "expected " + list + ", got " + describe(v));
    }

    /// A number > 0 (`max`: at most that, shown with `why`).
    double positive(std::string_view key, const json& v, double max = 0, std::string_view why = {}) const
    {
        const bool number = v.is_number();
        const double x = number ? v.get<double>() : 0;
        if (!number || !(x > 0) || (max > 0 && x > max))
            fail(key, "expected a number > 0" + (max > 0 ? " and <= " + number_text(max) + std::string(why) : "")
                          + ", got " + describe(v));
        return x;
    }

    /// A required key; `why` says what it is for.
    const json& required(std::string_view key, std::string_view why) const
    {
        const auto* v = find(key);
        if (!v)
            fail(key, "required key missing (" + std::string(why) + ")");
        return *v;
    }

private:
    const ConfigReader& r_;
    const json& object_;
    const std::string& pointer_;
};

/// "a rotary stage", "a goniometer".
std::string a_stage(StageKind kind)
{
    return kind == StageKind::Goniometer ? "a goniometer" : std::string("a ") + kind_name(kind) + " stage";
}

/// Keys that a stage of this kind and motor does not have: each refused at its pointer, naming
/// what the stage has instead.
void refuse_other_keys(const StageReader& k, const StageModel& s)
{
    for (const auto& key : kUnitKeys) {
        const auto wrong = s.angular() ? key.mm : key.deg;
        const auto right = s.angular() ? key.deg : key.mm;
        if (k.find(wrong))
            k.fail(wrong, a_stage(s.kind) + "'s unit is the " + (s.angular() ? "degree" : "mm") + ": "
                              + std::string(right) + ", not " + std::string(wrong));
    }
    if (k.find("travel_mm") && s.kind == StageKind::Rotary)
        k.fail("travel_mm", "a rotary stage turns without end: it has no travel");
    if (k.find("travel_mm") && s.kind == StageKind::Goniometer)
        k.fail("travel_mm", "a goniometer's travel is its angle_range_deg, not travel_mm");
    if (k.find("angle_range_deg") && s.kind == StageKind::Rotary)
        k.fail("angle_range_deg", "a rotary stage turns without end: it has no angle range (a goniometer has one)");
    if (k.find("angle_range_deg") && s.kind == StageKind::Linear)
        k.fail("angle_range_deg", "a linear stage's travel is its travel_mm, not an angle range");
    if (k.find("limit_switches") && s.kind == StageKind::Rotary)
        k.fail("limit_switches", "a rotary stage has no limit switches: a home switch once per turn");
    if (k.find("home_direction") && s.motor == MotorKind::Brushless)
        k.fail("home_direction", "a brushless channel always homes forward (p. 37)");
    for (const auto key : kPmdKeys)
        if (k.find(key) && s.motor != MotorKind::Brushless)
            k.fail(key, "PMD stage parameters (MOT_GET_PMDSTAGEAXISPARAMS, p. 75) belong to a brushless stage, not a "
                            + std::string(motor_name(s.motor)) + " one");
}

/// travel_mm (linear) or angle_range_deg (goniometer); a rotation stage has neither.
void read_travel(const ConfigReader& r, const StageReader& k, StageModel& s)
{
    switch (s.kind) {
    case StageKind::Linear:
        s.travel_mm = k.positive("travel_mm", k.required("travel_mm", "the travel of a linear stage"));
        return;
    case StageKind::Rotary:
        return;
    case StageKind::Goniometer: {
        const auto& range = k.required("angle_range_deg", "a goniometer's end stops: [min, max] in degrees");
        if (!range.is_array() || range.size() != 2)
            k.fail("angle_range_deg", "expected [min, max] in degrees, got " + describe(range));
        double ends[2];
        for (std::size_t i = 0; i < 2; ++i) {
            const auto& v = range[i];
            if (!v.is_number() || !(v.get<double>() >= -360) || !(v.get<double>() <= 360))
                r.fail(pointer_to(k.at("angle_range_deg"), i), "expected a number -360..360, got " + describe(v));
            ends[i] = v.get<double>();
        }
        if (!(ends[0] < ends[1]))
            k.fail("angle_range_deg", "expected min < max, got " + dump(range));
        s.angle_min_deg = ends[0];
        s.angle_max_deg = ends[1];
        return;
    }
    }
}

/// The travel in counts fits the 32-bit position counters.
void check_counter_range(const StageReader& k, const StageModel& s)
{
    const double span = s.kind == StageKind::Goniometer ? s.angle_max_deg - s.angle_min_deg : s.travel_mm;
    const auto key = s.kind == StageKind::Goniometer ? "angle_range_deg" : "travel_mm";
    if (s.kind != StageKind::Rotary && span * s.counts_per_mm > kMaxCounterCounts)
        k.fail(key, "the travel is " + number_text(span * s.counts_per_mm) + " counts at " + number_text(s.counts_per_mm)
                        + " " + (s.angular() ? "counts_per_deg" : "counts_per_mm")
                        + ": expected at most 2147483647 (the 32-bit position counter)");
}

/// The home offset: from 0 to the travel (a turn on a rotation stage).
void read_home_offset(const StageReader& k, StageModel& s)
{
    const auto key = s.angular() ? kHomeOffset.deg : kHomeOffset.mm;
    const auto* v = k.find(key);
    if (!v)
        return;
    const double max = s.kind == StageKind::Linear       ? s.travel_mm
                       : s.kind == StageKind::Goniometer ? s.angle_max_deg - s.angle_min_deg
                                                         : 360.0;
    const auto within = s.kind == StageKind::Linear       ? " (within travel_mm)"
                        : s.kind == StageKind::Goniometer ? " (within angle_range_deg)"
                                                          : " (a turn)";
    if (!v->is_number() || !(v->get<double>() >= 0) || !(v->get<double>() <= max))
        k.fail(key, "expected a number 0.." + number_text(max) + within + ", got " + describe(*v));
    s.home_offset_mm = v->get<double>();
}

/// limit_switches and home_direction: homing runs to a fitted switch.
void read_switches(const StageReader& k, StageModel& s)
{
    if (const auto* v = k.find("limit_switches"))
        s.limit_switches = k.choice("limit_switches", *v, kSwitches);
    // Default: home to the reverse switch, or to the only one there is.
    s.home_forward = s.limit_switches == LimitSwitches::Forward;
    if (const auto* v = k.find("home_direction")) {
        s.home_forward = k.choice("home_direction", *v, kHomeDirections);
        const auto missing = s.home_forward ? LimitSwitches::Reverse : LimitSwitches::Forward;
        if (s.limit_switches == missing)
            k.fail("home_direction", std::string("homing runs to the ") + (s.home_forward ? "forward" : "reverse")
                                         + " limit switch, and this stage has none there (limit_switches \""
                                         + (s.home_forward ? "reverse" : "forward") + "\")");
    }
}

void read_pmd(const ConfigReader& r, const StageReader& k, StageModel& s)
{
    if (const auto* v = k.find("pmd_stage_id"))
        s.pmd_stage_id = static_cast<std::uint16_t>(r.get_int(*v, k.at("pmd_stage_id"), 0, 65'535));
    if (const auto* v = k.find("pmd_part_number")) {
        s.pmd_part_number = r.get_string(*v, k.at("pmd_part_number"), "a string of 1..16 characters");
        if (s.pmd_part_number.empty() || s.pmd_part_number.size() > kMaxPartNumberLength)
            k.fail("pmd_part_number", "expected a string of 1..16 characters, got " + describe(*v));
    }
    if (const auto* v = k.find("pmd_max_velocity"))
        s.pmd_max_velocity = static_cast<std::int32_t>(r.get_int(*v, k.at("pmd_max_velocity"), 1, 2'147'483'647));
    if (const auto* v = k.find("pmd_max_acceleration"))
        s.pmd_max_acceleration =
            static_cast<std::int32_t>(r.get_int(*v, k.at("pmd_max_acceleration"), 1, 2'147'483'647));
}

} // namespace

const char* kind_name(StageKind kind)
{
    switch (kind) {
    case StageKind::Linear:
        return "linear";
    case StageKind::Rotary:
        return "rotary";
    case StageKind::Goniometer:
        return "goniometer";
    }
    return "linear";
}

const char* motor_name(MotorKind motor)
{
    switch (motor) {
    case MotorKind::DcServo:
        return "dc_servo";
    case MotorKind::Stepper:
        return "stepper";
    case MotorKind::Brushless:
        return "brushless";
    }
    return "dc_servo";
}

StageModel read_stage(const ConfigReader& r, const json& object, const std::string& pointer)
{
    r.check_keys(object, pointer, kStageKeys);
    const StageReader k(r, object, pointer);
    StageModel s;
    if (const auto* v = k.find("name")) {
        const auto expected = "a name of 1.." + std::to_string(kMaxNameLength) + " characters";
        s.name = r.get_string(*v, k.at("name"), expected);
        if (s.name.empty() || s.name.size() > kMaxNameLength)
            k.fail("name", "expected " + expected + ", got " + describe(*v));
    }
    if (const auto* v = k.find("about")) {
        // Notes for the reader of the file (sources, figures); the emulator keeps none of it.
        bool text = v->is_string();
        if (v->is_array()) {
            text = true;
            for (const auto& line : *v)
                text = text && line.is_string();
        }
        if (!text)
            k.fail("about", "expected a string or an array of strings, got " + describe(*v));
    }
    s.kind = k.choice("kind", k.required("kind", "\"linear\", \"rotary\" or \"goniometer\""), kKinds);
    s.motor = k.choice("motor", k.required("motor", "\"dc_servo\", \"stepper\" or \"brushless\""), kMotors);
    refuse_other_keys(k, s);

    const auto unit_key = [&](const UnitKey& key) { return s.angular() ? key.deg : key.mm; };
    read_travel(r, k, s);
    const auto counts = unit_key(kCounts);
    if (s.kind == StageKind::Rotary)
        s.counts_per_mm = k.positive(counts, k.required(counts, "encoder counts or microsteps per degree"),
                                     kMaxRotaryCountsPerDeg, " (a turn within the position counter)");
    else
        s.counts_per_mm = k.positive(counts, k.required(counts, s.angular() ? "encoder counts or microsteps per degree"
                                                                            : "encoder counts or microsteps per mm"));
    check_counter_range(k, s);
    const auto power_up = [&](const UnitKey& key, double& field, std::string_view why) {
        field = k.positive(unit_key(key), k.required(unit_key(key), why));
    };
    power_up(kMaxVelocity, s.max_velocity_mm_s, "the power-up VELPARAMS maximum velocity");
    power_up(kAcceleration, s.acceleration_mm_s2, "the power-up VELPARAMS acceleration");
    power_up(kHomeVelocity, s.home_velocity_mm_s, "the power-up HOMEPARAMS velocity");
    read_home_offset(k, s);
    if (const auto* v = k.find(unit_key(kAptVelocity)))
        s.velocity_per_mm_s = k.positive(unit_key(kAptVelocity), *v);
    if (const auto* v = k.find(unit_key(kAptAcceleration)))
        s.acceleration_per_mm_s2 = k.positive(unit_key(kAptAcceleration), *v);
    read_switches(k, s);
    read_pmd(r, k, s);
    return s;
}

} // namespace rigsim::apt
