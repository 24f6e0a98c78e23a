#include "emulator/apt/config.hpp"
#include "emulator/apt/eeprom_entries.hpp"

#include "emulator/apt/catalogue.hpp"
#include "emulator/apt/shipped_stages.hpp"
#include "emulator/apt/stage_file.hpp"
#include "emulator/core/config_reader.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::apt {
namespace {

using nlohmann::json;

/// Every key an "apt" object may hold; which ones a device has depends on its model's kind.
constexpr std::array<std::string_view, 9> kAptKeys{"stage",    "bays",  "serial_number",          "solenoid",
                                                    "actuator", "gauge", "hardware_max_voltage_v", "flipper",
                                                    "eeprom"};
constexpr std::array<std::string_view, 1> kSolenoidKeys{"interlock_fitted"};
constexpr std::array<std::string_view, 1> kFlipperKeys{"position"};
constexpr std::array<std::string_view, 1> kCardKeys{"channels"};
constexpr std::array<std::string_view, 4> kInertialKeys{"travel_mm", "position_mm", "step_forward_nm", "step_reverse_nm"};
constexpr std::array<std::string_view, 5> kActuatorKeys{"travel_um", "max_voltage_v", "response_ms", "hysteresis",
                                                        "creep"};
constexpr std::array<std::string_view, 7> kBayKeys{"travel_um", "max_voltage_v", "response_ms", "hysteresis",
                                                   "creep",     "strain_gauge",  "zero_time_ms"};
constexpr std::array<std::string_view, 6> kGaugeKeys{"mounted_on",         "route",       "noise_um", "seed",
                                                     "stiffness_n_per_um", "zero_time_ms"};

/// The keys of the "apt" object of a device of model `c`.
std::vector<std::string_view> keys_of(const ControllerModel& c)
{
    switch (c.kind) {
    case UnitKind::Motor:
        if (!c.built_in_stage.empty())   // an integrated unit: its stage is built in
            return {"serial_number", "eeprom"};
        return {"stage", "bays", "serial_number", "eeprom"};
    case UnitKind::Solenoid:
        return {"solenoid", "serial_number", "eeprom"};
    case UnitKind::Piezo:
        if (c.rack)   // its cards save nothing
            return {"hardware_max_voltage_v", "bays", "serial_number"};
        return {"actuator", "serial_number", "eeprom"};
    case UnitKind::StrainGauge:
        return {"gauge", "serial_number", "eeprom"};
    case UnitKind::Flipper:
        return {"flipper", "serial_number", "eeprom"};
    case UnitKind::Polariser:
        return {"serial_number", "eeprom"};
    case UnitKind::PiezoMotor:
        return {"actuators", "serial_number"};
    }
    return {};
}

/// What a model of `c` is, for messages: "a piezo controller".
std::string_view kind_noun(const ControllerModel& c)
{
    switch (c.kind) {
    case UnitKind::Motor:
        if (!c.built_in_stage.empty())
            return "an integrated stage";
        return c.rack ? "a motor rack" : "a motor controller";
    case UnitKind::Solenoid:
        return "a solenoid controller";
    case UnitKind::Piezo:
        return c.rack ? "a piezo rack" : "a piezo controller";
    case UnitKind::StrainGauge:
        return "a strain gauge reader";
    case UnitKind::Flipper:
        return "a flip mount";
    case UnitKind::Polariser:
        return "a polarisation controller";
    case UnitKind::PiezoMotor:
        return "a piezo motor controller";
    }
    return "";
}

/// The optional keys of one object: each reader sets its field only when the key is there.
class Keys {
public:
    Keys(const ConfigReader& r, const json& object, std::string pointer)
        : r_(r), object_(object), pointer_(std::move(pointer)) {}

    const json* find(std::string_view key) const { return ConfigReader::find(object_, key); }
    std::string at(std::string_view key) const { return pointer_to(pointer_, key); }

    /// A number (integer or not) in min..max; `range` shows them in the message.
    void number(std::string_view key, double& field, double min, double max, std::string_view range) const
    {
        if (const auto* v = find(key)) {
            if (!v->is_number() || !(v->get<double>() >= min) || !(v->get<double>() <= max))
                r_.fail(at(key), "expected a number " + std::string(range) + ", got " + describe(*v));
            field = v->get<double>();
        }
    }
    void integer(std::string_view key, int& field, int min, int max) const
    {
        if (const auto* v = find(key))
            field = static_cast<int>(r_.get_int(*v, at(key), min, max));
    }
    void flag(std::string_view key, bool& field) const
    {
        if (const auto* v = find(key)) {
            if (!v->is_boolean())
                r_.fail(at(key), "expected true or false, got " + describe(*v));
            field = v->get<bool>();
        }
    }
    /// A piezo voltage rating: 75, 100 or 150 V (TPZ_IOSETTINGS VoltageLimit, p. 115; the
    /// BPC30x hardware limits of PZSTATUSBITS, p. 102).
    void voltage(std::string_view key, int& field) const
    {
        if (const auto* v = find(key)) {
            const bool ok = v->is_number_integer() && (*v == 75 || *v == 100 || *v == 150);
            if (!ok)
                r_.fail(at(key), "expected 75, 100 or 150, got " + describe(*v));
            field = v->get<int>();
        }
    }

private:
    const ConfigReader& r_;
    const json& object_;
    std::string pointer_;
};

/// The actuator keys of a TPZ001/KPZ101's "actuator" or a BPC30x bay object.
void load_actuator(const Keys& k, PiezoActuatorConfig& a)
{
    // GET_MAXTRAVEL reports the travel as a 16-bit word of 100 nm (p. 118).
    k.number("travel_um", a.travel_um, 0.1, 6553.5, "0.1..6553.5");
    k.voltage("max_voltage_v", a.max_voltage_v);
    k.number("response_ms", a.response_ms, 0.1, 1000, "0.1..1000");
    k.number("hysteresis", a.hysteresis, 0, 0.3, "0..0.3");
    k.number("creep", a.creep, 0, 0.05, "0..0.05");
}

/// `value` at `pointer` must be an object holding no key outside `allowed`.
template <std::size_t N>
Keys object_keys(const ConfigReader& r, const json& value, const std::string& pointer,
                 const std::array<std::string_view, N>& allowed)
{
    r.check_keys(value, pointer, allowed);
    return Keys(r, value, pointer);
}

/// The shipped stage a motor controller drives when its "apt" object names none.
constexpr std::string_view kDefaultStage = "MTS50-Z8";

/// The power-up velocity figures of the stage object `stage` at `pointer` come out on
/// `controller` as APT units (7.1) its 32-bit words hold, and not as 0.
void check_apt_units(const ConfigReader& r, const std::string& pointer, const StageModel& stage,
                     const ControllerModel& controller, const std::string& model)
{
    const bool angular = stage.angular();
    const struct {
        std::string_view key;
        double value;
        double stage_scale;   ///< per unit; 0: the controller's per count
        double per_count;
    } figures[]{
        {angular ? "max_velocity_deg_s" : "max_velocity_mm_s", stage.max_velocity_mm_s, stage.velocity_per_mm_s,
         controller.velocity_per_count_s},
        {angular ? "acceleration_deg_s2" : "acceleration_mm_s2", stage.acceleration_mm_s2,
         stage.acceleration_per_mm_s2, controller.acceleration_per_count_s2},
        {angular ? "home_velocity_deg_s" : "home_velocity_mm_s", stage.home_velocity_mm_s, stage.velocity_per_mm_s,
         controller.velocity_per_count_s},
    };
    for (const auto& f : figures) {
        // As MotorChannel scales them (rounded to the nearest unit).
        const double units = f.stage_scale > 0 ? f.value * f.stage_scale
                                               : f.value * driven_stage(controller, stage).counts_per_mm * f.per_count;
        const double word = std::round(units);
        if (!(word >= 1) || word > 2'147'483'647.0) {
            char shown[32];
            std::snprintf(shown, sizeof shown, "%.15g", word);
            r.fail(pointer_to(pointer, f.key), "gives " + std::string(shown) + " APT units on a " + model
                                                   + " (7.1 scaling): expected 1..2147483647");
        }
    }
}

/// The travel of the stage object `stage` in the counts `controller` counts (a later-generation
/// stepper's finer microsteps, driven_stage) fits the 32-bit position counter; the stage file's
/// own counts are checked as it is read.
void check_driven_travel(const ConfigReader& r, const std::string& pointer, const StageModel& stage,
                         const ControllerModel& controller, const std::string& model)
{
    const double span = stage.kind == StageKind::Goniometer ? stage.angle_max_deg - stage.angle_min_deg : stage.travel_mm;
    const double counts = span * driven_stage(controller, stage).counts_per_mm;
    if (stage.kind == StageKind::Rotary || controller.counts_per_stage_count == 1 || counts <= 2'147'483'647.0)
        return;
    char shown[32];
    std::snprintf(shown, sizeof shown, "%.15g", std::round(counts));
    r.fail(pointer_to(pointer, stage.kind == StageKind::Goniometer ? "angle_range_deg" : "travel_mm"),
           "the travel is " + std::string(shown) + " counts on a " + model + " at firmware "
               + std::string(firmware_name(controller.firmware)) + " (" + std::to_string(static_cast<int>(
                   controller.counts_per_stage_count)) + " x the stage's counts): expected at most 2147483647 "
               "(the 32-bit position counter)");
}

/// A single unit's "stage" or one of a rack's "bays": a shipped stage's name, or a stage object
/// (stage_file.hpp); either with the motor `controller` drives.
StageModel load_stage(const ConfigReader& r, const json& v, const std::string& pointer,
                      const ControllerModel& controller, const std::string& model)
{
    if (v.is_string()) {
        const auto& name = v.get_ref<const std::string&>();
        const auto* found = find_stage(name);
        if (!found)
            r.fail(pointer, "unknown stage " + quote(name) + " (expected one of " + stage_names()
                                + ", or a stage object)");
        if (const auto* owner = built_into(name); owner && owner->name != model)
            r.fail(pointer, "stage " + quote(name) + " is the stage built into the " + std::string(owner->name)
                                + ", which no other controller drives");
        if (found->motor != controller.motor)
            r.fail(pointer, "stage " + quote(name) + " has another kind of motor than a " + model);
        return *found;
    }
    if (!v.is_object())
        r.fail(pointer, "expected the name of a shipped stage or a stage object, got " + describe(v));
    // A shipped name on another description would make two stages of one name.
    if (const auto* name = ConfigReader::find(v, "name"); name && name->is_string()) {
        const auto& text = name->get_ref<const std::string&>();
        if (find_stage(text))
            r.fail(pointer_to(pointer, "name"),
                   quote(text) + " names the shipped stage " + text + ": use the name alone or another name");
    }
    auto stage = read_stage(r, v, pointer);
    if (stage.motor != controller.motor)
        r.fail(pointer_to(pointer, "motor"), "expected " + quote(motor_name(controller.motor)) + " (the motor a "
                                                 + model + " drives), got " + quote(motor_name(stage.motor)));
    check_apt_units(r, pointer, stage, controller, model);
    check_driven_travel(r, pointer, stage, controller, model);
    return stage;
}

/// A motor controller's "stage", or a motor rack's "bays".
void load_motor(const ConfigReader& r, const json& a, const std::string& apt_pointer, const ControllerModel& controller,
                const std::string& model, AptConfig& apt)
{
    if (!controller.built_in_stage.empty()) {
        const auto* stage = find_stage(controller.built_in_stage);
        if (!stage)
            throw ConfigError("config/stages/" + std::string(controller.built_in_stage) + ".json: the stage built into the "
                              + model + " is not shipped");
        apt.stage = *stage;
        return;
    }
    if (const auto* st = r.find(a, "stage"))
        apt.stage = load_stage(r, *st, pointer_to(apt_pointer, "stage"), controller, model);
    if (controller.rack) {
        if (r.find(a, "stage"))
            r.fail(pointer_to(apt_pointer, "stage"), "a rack controller names a stage per bay in \"bays\"");
        const auto bays_pointer = pointer_to(apt_pointer, "bays");
        const auto& bays = r.require(a, apt_pointer, "bays");
        const auto max = static_cast<std::size_t>(controller.max_bays);
        if (!bays.is_array() || bays.empty() || bays.size() > max)
            r.fail(bays_pointer, "expected an array of 1.." + std::to_string(max) + " stages, got " + describe(bays));
        for (std::size_t i = 0; i < bays.size(); ++i)
            apt.bays.push_back(load_stage(r, bays[i], pointer_to(bays_pointer, i), controller, model));
    } else if (r.find(a, "bays")) {
        r.fail(pointer_to(apt_pointer, "bays"), "only rack controllers have bays; " + model + " names one \"stage\"");
    } else if (!r.find(a, "stage") && apt.stage.motor != controller.motor) {
        r.fail(pointer_to(apt_pointer, "stage"),
               "required key missing (the default " + apt.stage.name + " is not a stage for a " + model + ")");
    }
}

/// One piezo channel's object (a BPC30x bay, a channel of an MMR601's MPZ601 card) at `pointer`.
PiezoBayConfig load_piezo_channel(const ConfigReader& r, const json& object, const std::string& pointer,
                                  const AptConfig& apt)
{
    const auto bay_keys = object_keys(r, object, pointer, kBayKeys);
    PiezoBayConfig bay;
    load_actuator(bay_keys, bay.actuator);
    bay_keys.flag("strain_gauge", bay.strain_gauge);
    bay_keys.integer("zero_time_ms", bay.zero_time_ms, 0, 60'000);
    if (bay.actuator.max_voltage_v > apt.hardware_max_voltage_v)
        r.fail(bay_keys.at("max_voltage_v"), "expected at most the rack's hardware_max_voltage_v (" +
                                                 std::to_string(apt.hardware_max_voltage_v) + "), got " +
                                                 std::to_string(bay.actuator.max_voltage_v));
    return bay;
}

/// A BPC30x: "hardware_max_voltage_v" and a bay object per occupied slot (default: every slot,
/// each with the defaults). An MMR601: a bay object per MPZ601 card, `{"channels": [ch1, ch2]}`
/// (each a BPC bay's keys; default: both with the defaults); apt.piezo_bays holds every card's two.
void load_piezo_rack(const ConfigReader& r, const Keys& k, const ControllerModel& controller, AptConfig& apt)
{
    k.voltage("hardware_max_voltage_v", apt.hardware_max_voltage_v);
    const auto max = static_cast<std::size_t>(controller.max_bays);
    const auto per_bay = static_cast<std::size_t>(controller.bay_channels);
    const auto* bays = k.find("bays");
    if (!bays) {
        apt.piezo_bays.resize(max * per_bay);
        return;
    }
    if (!bays->is_array() || bays->empty() || bays->size() > max) {
        const auto count = max == 1 ? std::string("1 bay") : "1.." + std::to_string(max) + " bays";
        r.fail(k.at("bays"), "expected an array of " + count + ", got " + describe(*bays));
    }
    for (std::size_t i = 0; i < bays->size(); ++i) {
        const auto bay_pointer = pointer_to(k.at("bays"), i);
        if (per_bay > 1) {
            const auto card = object_keys(r, (*bays)[i], bay_pointer, kCardKeys);
            const auto* channels = card.find("channels");
            if (channels && (!channels->is_array() || channels->size() != per_bay))
                r.fail(card.at("channels"), "expected an array of " + std::to_string(per_bay) + " channel objects, got "
                                                + describe(*channels));
            for (std::size_t c = 0; c < per_bay; ++c)
                apt.piezo_bays.push_back(channels ? load_piezo_channel(r, (*channels)[c], pointer_to(card.at("channels"), c), apt)
                                                  : PiezoBayConfig{});
            continue;
        }
        apt.piezo_bays.push_back(load_piezo_channel(r, (*bays)[i], bay_pointer, apt));
    }
}

/// A KIM101/TIM101's "actuators": one object per channel from channel 1 (at most the model's
/// channels); the channels it does not name get the default actuator (a PIA13 at mid-travel).
void load_inertial_actuators(const ConfigReader& r, const Keys& k, const ControllerModel& c, AptConfig& apt)
{
    const auto channels = static_cast<std::size_t>(c.pzmot_channels);
    apt.inertial_actuators.assign(channels, InertialActuatorConfig{});
    const auto* list = k.find("actuators");
    if (!list)
        return;
    if (!list->is_array() || list->empty() || list->size() > channels)
        r.fail(k.at("actuators"), "expected an array of 1.." + std::to_string(channels) + " actuator objects, got "
                                      + describe(*list));
    for (std::size_t i = 0; i < list->size(); ++i) {
        const auto at = pointer_to(k.at("actuators"), i);
        const auto keys = object_keys(r, (*list)[i], at, kInertialKeys);
        auto& a = apt.inertial_actuators[i];
        keys.number("travel_mm", a.travel_mm, 0.001, 1000, "from 0.001 to 1000");
        a.position_mm = a.travel_mm / 2;
        keys.number("position_mm", a.position_mm, 0, a.travel_mm, "from 0 to travel_mm");
        keys.number("step_forward_nm", a.step_forward_nm, 0.001, 10'000, "from 0.001 to 10000");
        keys.number("step_reverse_nm", a.step_reverse_nm, 0.001, 10'000, "from 0.001 to 10000");
    }
}

/// A strain gauge reader's "gauge" object at `pointer`.
StrainGaugeConfig load_gauge(const ConfigReader& r, const json& g, const std::string& pointer)
{
    const auto k = object_keys(r, g, pointer, kGaugeKeys);
    StrainGaugeConfig gauge;
    if (const auto* v = k.find("mounted_on"))
        gauge.mounted_on = r.get_string(*v, k.at("mounted_on"), "the name of a TPZ001 or KPZ101 device");
    if (const auto* v = k.find("route")) {
        static const std::map<std::string, GaugeRoute> routes{
            {"hub_a", GaugeRoute::HubA}, {"hub_b", GaugeRoute::HubB}, {"sma", GaugeRoute::Sma}};
        const auto found = v->is_string() ? routes.find(v->get<std::string>()) : routes.end();
        if (found == routes.end())
            r.fail(k.at("route"), "expected \"hub_a\", \"hub_b\" or \"sma\", got " + describe(*v));
        gauge.route = found->second;
    }
    k.number("noise_um", gauge.noise_um, 0, 1, "0..1");
    if (const auto* v = k.find("seed"))
        gauge.seed = static_cast<std::uint32_t>(r.get_int(*v, k.at("seed"), 0, 4'294'967'295LL));
    k.number("stiffness_n_per_um", gauge.stiffness_n_per_um, std::nextafter(0.0, 1.0), 1e6, "> 0 and <= 1000000");
    k.integer("zero_time_ms", gauge.zero_time_ms, 0, 60'000);
    return gauge;
}

/// The "eeprom" object: state file entries, each "bay<N>/0x<id>" (the form eeprom_key writes)
/// with its data in hex; whether the unit saves and takes each, its device checks at power-up.
std::map<std::string, std::string> load_eeprom(const ConfigReader& r, const json& e, const std::string& pointer)
{
    if (!e.is_object())
        r.fail(pointer, "expected an object of \"bay<N>/0x<id>\": \"<hex data>\" entries, got " + describe(e));
    std::map<std::string, std::string> out;
    for (const auto& item : e.items()) {
        const auto at = pointer_to(pointer, item.key());
        if (!parse_eeprom_key(item.key()))
            r.fail(at, "expected a key bay<N>/0x<4 lower-case hex digits> (a state file's), got " + quote(item.key()));
        if (!item.value().is_string())
            r.fail(at, "expected a string of hex digits, got " + describe(item.value()));
        std::string data;
        std::string why;
        if (!from_hex(item.value().get<std::string>(), data, why))
            r.fail(at, why);
        out.emplace(item.key(), item.value().get<std::string>());
    }
    return out;
}

/// Every key of `a` is one of the model's: a key of another kind of unit names what this
/// one holds instead.
void check_apt_keys(const ConfigReader& r, const json& a, const std::string& apt_pointer,
                    const ControllerModel& controller, const std::string& model)
{
    if (!a.is_object())
        r.fail(apt_pointer, "expected an object, got " + describe(a));
    const auto keys = keys_of(controller);
    for (const auto& item : a.items()) {
        if (std::find(keys.begin(), keys.end(), item.key()) != keys.end())
            continue;
        if (std::find(kAptKeys.begin(), kAptKeys.end(), item.key()) == kAptKeys.end())
            r.check_keys(a, apt_pointer, keys.data(), keys.size());   // an unknown key: throws
        std::string list;
        for (const auto key : keys)
            list += (list.empty() ? "" : ", ") + std::string(key);
        r.fail(pointer_to(apt_pointer, item.key()),
               model + " is " + std::string(kind_noun(controller)) + ": its keys are " + list);
    }
}

/// The "apt" object `a` at `apt_pointer` of a device whose model is `controller`.
AptConfig load_apt(const ConfigReader& r, const json& a, const std::string& apt_pointer,
                   const ControllerModel& controller, const std::string& model)
{
    AptConfig apt;
    check_apt_keys(r, a, apt_pointer, controller, model);
    const Keys k(r, a, apt_pointer);
    switch (controller.kind) {
    case UnitKind::Motor:
        load_motor(r, a, apt_pointer, controller, model, apt);
        break;
    case UnitKind::Solenoid:
        if (const auto* s = k.find("solenoid"))
            object_keys(r, *s, k.at("solenoid"), kSolenoidKeys).flag("interlock_fitted", apt.solenoid.interlock_fitted);
        break;
    case UnitKind::Piezo:
        if (controller.rack)
            load_piezo_rack(r, k, controller, apt);
        else if (const auto* act = k.find("actuator"))
            load_actuator(object_keys(r, *act, k.at("actuator"), kActuatorKeys), apt.actuator);
        break;
    case UnitKind::StrainGauge:
        if (const auto* g = k.find("gauge"))
            apt.gauge = load_gauge(r, *g, k.at("gauge"));
        break;
    case UnitKind::Flipper:
        if (const auto* f = k.find("flipper"))
            object_keys(r, *f, k.at("flipper"), kFlipperKeys).integer("position", apt.flipper.position, 1, 2);
        break;
    case UnitKind::Polariser:
        break;
    case UnitKind::PiezoMotor:
        load_inertial_actuators(r, k, controller, apt);
        break;
    }
    if (const auto* sn = k.find("serial_number")) {
        const std::int64_t lo = controller.serial_prefix * 1'000'000LL;
        apt.serial_number = static_cast<std::uint32_t>(
            r.get_int(*sn, k.at("serial_number"), lo, lo + 999'999, " (the model's serial prefix)"));
    }
    if (const auto* e = k.find("eeprom"))
        apt.eeprom = load_eeprom(r, *e, k.at("eeprom"));
    return apt;
}

/// A single-unit piezo controller: what a strain gauge reader may be mounted on.
bool carries_gauges(const DeviceConfig& d)
{
    const auto* c = d.protocol == "apt" ? find_controller(d.model) : nullptr;
    return c && c->kind == UnitKind::Piezo && !c->rack;
}

} // namespace

StageModel default_stage()
{
    const auto* stage = find_stage(kDefaultStage);
    if (!stage)
        throw ConfigError("config/stages/" + std::string(kDefaultStage) + ".json: the default stage is not shipped");
    return *stage;
}

void load_device_section(const ConfigReader& reader, const json& device, const std::string& pointer,
                         DeviceConfig& config)
{
    const bool named = reader.find(device, "model") != nullptr;
    const auto* controller = find_controller(config.model);
    if (!named || !controller)
        reader.fail(pointer_to(pointer, "model"), "expected an APT controller model (" +
                                                      std::string(controller_names()) + "), got " +
                                                      (named ? quote(config.model) : std::string("nothing")));
    // A unit made after the 2012 manual has the later generation only (its default).
    if (config.firmware.empty())
        config.firmware = firmware_name(controller->later_only ? Firmware::Issue44_1 : Firmware::Issue3);
    const auto firmware = find_firmware(config.firmware);
    if (!firmware)
        reader.fail(pointer_to(pointer, "firmware"), "unknown APT firmware generation " + quote(config.firmware) +
                                                         " (expected " + std::string(firmware_names()) + ")");
    if (controller->later_only && *firmware == Firmware::Issue3)
        reader.fail(pointer_to(pointer, "firmware"),
                    "the " + config.model + " was made after the 2012 manual: it has the later generation only (expected "
                        + quote(std::string(firmware_name(Firmware::Issue44_1))) + ")");
    // The "apt" object is checked against the controller as its generation shapes it (the
    // scaling of the power-up velocities).
    const auto& a = reader.require(device, pointer, "apt");
    auto apt = load_apt(reader, a, pointer_to(pointer, "apt"), *find_controller(config.model, *firmware), config.model);
    apt.firmware = *firmware;
    config.section = std::move(apt);
}

void validate_rig(const ConfigReader& reader, const RigConfig& rig)
{
    std::map<std::string, std::string> carried;   // piezo device name -> pointer of its gauge's device
    for (std::size_t i = 0; i < rig.devices.size(); ++i) {
        const auto& d = rig.devices[i];
        const auto* c = d.protocol == "apt" ? find_controller(d.model) : nullptr;
        if (!c || c->kind != UnitKind::StrainGauge || config_of(d).gauge.mounted_on.empty())
            continue;
        const auto& name = config_of(d).gauge.mounted_on;
        const auto device_pointer = pointer_to("/devices", i);
        const auto pointer = pointer_to(pointer_to(pointer_to(device_pointer, "apt"), "gauge"), "mounted_on");
        const auto piezo = std::find_if(rig.devices.begin(), rig.devices.end(),
                                        [&](const DeviceConfig& other) { return other.name == name; });
        if (piezo == rig.devices.end())
            reader.fail(pointer, "no device named " + quote(name) + " in the rig");
        if (!carries_gauges(*piezo))
            reader.fail(pointer, "device " + quote(name) + " (" + piezo->model +
                                     ") is not a piezo controller (TPZ001, KPZ101)");
        const auto [it, first] = carried.emplace(name, device_pointer);
        if (!first)
            reader.fail(pointer, "device " + quote(name) + " already has a gauge: " + it->second);
    }
}

} // namespace rigsim::apt
