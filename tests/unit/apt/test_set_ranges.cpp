// The SET field ranges: each parameter block lists its own beside its fields (RIGSIM_APT_RANGES in
// the codec), and out_of_range() walks them in that order.
#include "emulator/apt/codec.hpp"
#include "emulator/apt/set_ranges.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <variant>

namespace test_set_ranges {

using namespace rigsim::apt;

namespace {

template <class T, class = void> constexpr bool kHasRanges = false;
template <class T> constexpr bool kHasRanges<T, std::void_t<decltype(T::has_ranges)>> = true;

template <class T> struct IsSet : std::false_type {};
template <class P> struct IsSet<msg::Set<P>> : std::true_type {};

/// The IDs of the SETs whose block lists ranges, and each list's entries checked for sense.
struct RangedSets {
    std::set<std::uint16_t> ids;
    std::set<std::string> bad;   // "<id> <name>": an empty range, an empty or repeated name
};

template <class T> void add(RangedSets& out)
{
    if constexpr (IsSet<T>::value) {
        if constexpr (kHasRanges<typename T::Params>) {
            out.ids.insert(T::id);
            const typename T::Params block{};
            std::set<std::string_view> names;
            for (const auto& r : T::Params::ranges(block))
                if (r.name.empty() || r.min > r.max || !names.insert(r.name).second)
                    out.bad.insert(std::to_string(T::id) + " " + std::string(r.name));
        }
    }
}

template <class... Ts> void add_chapter(RangedSets& out, const std::variant<Ts...>*) { (add<Ts>(out), ...); }
template <class... C> void add_chapters(RangedSets& out, const std::tuple<C...>*)
{
    (add_chapter(out, static_cast<const typename C::variant*>(nullptr)), ...);
}

std::optional<std::string> check(const msg::Message& m, bool wheel = true)
{
    return out_of_range(m, wheel);
}

} // namespace

TEST_CASE("set ranges: the first field out of range is named with its value and its range, in the block's order",
          "[unit][apt][set_ranges]")
{
    msg::SetVelParams vel{{1, 0, 100, 200}};
    CHECK_FALSE(check(vel));
    vel.params.acceleration = 0;
    CHECK(check(vel) == "acceleration 0 (1..2147483647)");
    vel.params.min_velocity = -1;
    CHECK(check(vel) == "minimum velocity -1 (0..2147483647)");

    msg::SetPmdMotorOutputParams out{};
    out.params.motor_bias = -32768;
    CHECK(check(out) == "MotorBias -32768 (-32767..32767)");
    msg::SetSolCycleParams cycle{{1, 399, 4000, 0}};
    CHECK(check(cycle) == "OnTime 399 (400..40000000)");
    msg::SetTsgIoSettings tsg{};
    tsg.params.hub_analogue_output = 1;
    tsg.params.display_mode = 1;
    CHECK(check(tsg) == "ForceCalib 0 (1..65535)");
}

TEST_CASE("set ranges: the KCUBEMMIPARAMS wheel words are checked on a unit with a wheel only",
          "[unit][apt][set_ranges]")
{
    msg::SetKCubeMmiParams mmi{};
    mmi.params.js_mode = 0;
    mmi.params.disp_brightness = 50;
    CHECK(check(mmi, true) == "JSMode 0 (1..3)");
    CHECK_FALSE(check(mmi, false));   // a KSC101: ksc.py sends the "unused" wheel words as 0
    mmi.params.disp_timeout = 481;
    CHECK(check(mmi, false) == "DispTimeout 481 (0..480)");
}

TEST_CASE("set ranges: GETs, REQs and blocks without ranges take any value", "[unit][apt][set_ranges]")
{
    CHECK_FALSE(check(msg::GetVelParams{}));   // a SET's all-zero block would be out of range
    CHECK_FALSE(check(msg::ReqVelParams{}));
    CHECK_FALSE(check(msg::SetPosCounter{{1, -5}}));
    CHECK_FALSE(check(msg::SetKpzMmiParams{}));   // the K-Cube units' own blocks: kcube_units.cpp
}

TEST_CASE("set ranges: the 26 SETs with ranges, each range named once and not empty", "[unit][apt][set_ranges]")
{
    RangedSets sets;
    add_chapters(sets, static_cast<const msg::Chapters*>(nullptr));
    CHECK(sets.bad.empty());
    CHECK(sets.ids
          == std::set<std::uint16_t>{MGMSG_MOT_SET_VELPARAMS, MGMSG_MOT_SET_JOGPARAMS, MGMSG_MOT_SET_DCPIDPARAMS,
                                     MGMSG_MOT_SET_BUTTONPARAMS, MGMSG_MOT_SET_PMDPOSITIONLOOPPARAMS,
                                     MGMSG_MOT_SET_PMDMOTOROUTPUTPARAMS, MGMSG_MOT_SET_PMDTRACKSETTLEPARAMS,
                                     MGMSG_MOT_SET_PMDPROFILEMODEPARAMS, MGMSG_MOT_SET_PMDCURRENTLOOPPARAMS,
                                     MGMSG_MOT_SET_PMDSETTLEDCURRENTLOOPPARAMS, MGMSG_MOT_SET_SOL_CYCLEPARAMS,
                                     MGMSG_PZ_SET_OUTPUTPOS, MGMSG_PZ_SET_INPUTVOLTSSRC, MGMSG_PZ_SET_PICONSTS,
                                     MGMSG_PZ_SET_TPZ_DISPSETTINGS, MGMSG_PZ_SET_TPZ_IOSETTINGS,
                                     MGMSG_PZ_SET_OUTPUTMAXVOLTS, MGMSG_PZ_SET_TPZ_SLEWRATES,
                                     MGMSG_PZ_SET_TSG_IOSETTINGS, MGMSG_MOT_SET_POWERPARAMS,
                                     MGMSG_MOT_SET_KCUBEMMIPARAMS, MGMSG_MOT_SET_KCUBETRIGIOCONFIG,
                                     MGMSG_MOT_SET_KCUBEPOSTRIGPARAMS, MGMSG_MOT_SET_KCUBEKSTLOOPPARAMS,
                                     MGMSG_MOT_SET_MFF_OPERPARAMS, MGMSG_MOT_SET_POLPARAMS});
}

} // namespace test_set_ranges
