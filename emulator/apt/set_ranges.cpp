#include "emulator/apt/set_ranges.hpp"

#include <string>
#include <type_traits>

namespace rigsim::apt {

namespace {

// The ranges are the codec's: each parameter block lists its own beside its fields
// (RIGSIM_APT_RANGES in codec_*.hpp, the manual's page or the public source at each). This file
// walks them.

/// True for a message or block that lists ranges (RIGSIM_APT_RANGES).
template <class T, class = void> constexpr bool kHasRanges = false;
template <class T> constexpr bool kHasRanges<T, std::void_t<decltype(T::has_ranges)>> = true;

template <class T> struct IsSet : std::false_type {};
template <class P> struct IsSet<msg::Set<P>> : std::true_type {};

template <class Ranges> std::optional<std::string> first_out_of_range(const Ranges& fields, bool mmi_wheel)
{
    for (const auto& r : fields) {
        if (r.read_by == msg::ReadBy::WheelUnit && !mmi_wheel)
            continue;
        if (r.value < r.min || r.value > r.max)
            return std::string(r.name) + " " + std::to_string(r.value) + " (" + std::to_string(r.min) + ".."
                   + std::to_string(r.max) + ")";
    }
    return std::nullopt;
}

/// The ranges of message `m`: a SET's block's, or those a message of one struct lists itself.
template <class T> std::optional<std::string> out_of_range_of(const T& m, bool mmi_wheel)
{
    if constexpr (IsSet<T>::value) {
        if constexpr (kHasRanges<typename T::Params>)
            return first_out_of_range(T::Params::ranges(m.params), mmi_wheel);
        else
            return std::nullopt;
    } else if constexpr (std::is_same_v<T, msg::PzmotSetParams>) {
        // A PZMOT sub-message: its block's ranges (issue 37 p. 372-401).
        return std::visit(
            [mmi_wheel](const auto& block) -> std::optional<std::string> {
                using B = std::decay_t<decltype(block)>;
                if constexpr (kHasRanges<B>)
                    return first_out_of_range(B::ranges(block), mmi_wheel);
                else
                    return std::nullopt;
            },
            m.block);
    } else if constexpr (kHasRanges<T>) {
        return first_out_of_range(T::ranges(m), mmi_wheel);
    } else {
        return std::nullopt;
    }
}

} // namespace

std::optional<std::string> out_of_range(const msg::Message& m, bool mmi_wheel)
{
    return msg::visit([mmi_wheel](const auto& typed) { return out_of_range_of(typed, mmi_wheel); }, m);
}

} // namespace rigsim::apt
