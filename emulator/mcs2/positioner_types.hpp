#pragma once
// MCS2 positioner types (SmarAct "MCS2 Positioner Types" 1.0.4, Table 1.1 and the cross reference
// of Table 1.2): the type code a channel is configured with (Positioner Type, guide 4.4.6), its
// name, the sensor it reads and how it is referenced. What rigsim does with them: the kind of body
// (linear, rotary, goniometer), the unit (pm or n°, guide 4.8.3-4.8.4) and the referencing
// sequence (single mark, distance-coded marks, end stop: guide 2.7).

#include <cstdint>
#include <string_view>

namespace rigsim::mcs2 {

enum class Motion { Linear, Rotary, Goniometer };
/// Positioner Reference Type (guide 4.8.6): 0 NONE, 1 END_STOP, 2 SINGLE_CODED, 3 DISTANCE_CODED.
enum class Reference : std::int32_t { None = 0, EndStop = 1, SingleMark = 2, DistanceCoded = 3 };

struct PositionerType {
    std::int32_t code;
    std::string_view name;     ///< Positioner Type Name (4.4.7): "SL...S1SS"
    Motion motion;
    char sensor;               ///< 'S', 'L', 'M', 'P' (PicoScale)
    Reference reference;
};

/// The type with this code, or nullptr (0, the custom slots 250-253 and unknown codes).
const PositionerType* positioner_type(std::int32_t code);
/// Every code, comma-separated (for config messages).
std::string_view positioner_type_codes();

} // namespace rigsim::mcs2
