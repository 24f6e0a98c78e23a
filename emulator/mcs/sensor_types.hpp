#pragma once
// Sensor types of the MCS manual, appendix 4.3.

#include <optional>
#include <string_view>

namespace rigsim::mcs {

/// What a sensor measures: linear channels answer GP/MPA/MPR; rotary and goniometer
/// channels answer GA/MAA/MAR (section 2.3.1) and refuse the linear commands with 143.
enum class SensorKind { Linear, Rotary, Goniometer };

/// How FRM references the positioner (appendix 4.3, "Reference Type").
enum class ReferenceType { Mark, DistanceCodedMarks, EndStop, None };

struct SensorType {
    int code;
    std::string_view symbol;
    std::string_view series;
    SensorKind kind;
    ReferenceType reference;
};

/// The entry of appendix 4.3 with this type code, if any.
const SensorType* sensor_type_by_code(int code);
/// The entry of appendix 4.3 with this symbol ("S", "SR", "G605S", ...), if any.
const SensorType* sensor_type_by_symbol(std::string_view symbol);
/// Every symbol of appendix 4.3, comma-separated (for error messages).
std::string_view sensor_type_symbols();

} // namespace rigsim::mcs
