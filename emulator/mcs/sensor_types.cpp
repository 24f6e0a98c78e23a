#include "emulator/mcs/sensor_types.hpp"

#include <array>

namespace rigsim::mcs {
namespace {

using K = SensorKind;
using R = ReferenceType;

// Appendix 4.3, in the manual's order. '*' marks (multiple, distance-coded) are
// DistanceCodedMarks.
constexpr std::array<SensorType, 29> kSensorTypes{{
    {1, "S", "SLCxxxxs", K::Linear, R::Mark},
    {2, "SR", "SR36xxs, SR3511s, SR5714s, SR7021s, SR2812s", K::Rotary, R::Mark},
    {5, "SP", "SLCxxxrs", K::Linear, R::Mark},
    {6, "SC", "SLCxxxsc", K::Linear, R::DistanceCodedMarks},
    {8, "SR20", "SR2013s, SR1612s", K::Rotary, R::Mark},
    {9, "M", "SLCxxxm", K::Linear, R::EndStop},
    {11, "GD", "SGO60.5m", K::Goniometer, R::EndStop},
    {12, "GE", "SGO77.5m", K::Goniometer, R::EndStop},
    {14, "GF", "SR1209m", K::Rotary, R::EndStop},
    {16, "G605S", "SGO60.5s", K::Goniometer, R::Mark},
    {17, "G775S", "SGO77.5s", K::Goniometer, R::Mark},
    {18, "SC500", "SLLxxsc", K::Linear, R::DistanceCodedMarks},
    {19, "G955S", "SGO95.5s", K::Goniometer, R::Mark},
    {20, "SR77", "SR77xxs", K::Rotary, R::Mark},
    {21, "SD", "SLCxxxds, SLLxxs", K::Linear, R::Mark},
    {22, "R20ME", "SR2013sx, SR1410sx", K::Rotary, R::Mark},
    {23, "SR2", "SR36xxs, SR3511s, SR5714s, SR7021s, SR2812s", K::Rotary, R::Mark},
    {24, "SCD", "SLCxxxsc", K::Linear, R::DistanceCodedMarks},
    {25, "SRC", "SR7021sc", K::Rotary, R::DistanceCodedMarks},
    {26, "SR36M", "SR3610m", K::Rotary, R::None},
    {27, "SR36ME", "SR3610m", K::Rotary, R::EndStop},
    {28, "SR50M", "SR5018m", K::Rotary, R::None},
    {29, "SR50ME", "SR5018m", K::Rotary, R::EndStop},
    {30, "G1045S", "SGO104.5s", K::Goniometer, R::Mark},
    {31, "G1395S", "SGO139.5s", K::Goniometer, R::Mark},
    {32, "MD", "SLCxxxmdme", K::Linear, R::EndStop},
    {33, "G935M", "SGO93.5me", K::Goniometer, R::EndStop},
    {34, "SHL20", "SHL-20", K::Linear, R::Mark},
    {35, "SCT", "SLCxxxscu", K::Linear, R::DistanceCodedMarks},
}};

} // namespace

const SensorType* sensor_type_by_code(int code)
{
    for (const auto& t : kSensorTypes)
        if (t.code == code)
            return &t;
    return nullptr;
}

const SensorType* sensor_type_by_symbol(std::string_view symbol)
{
    for (const auto& t : kSensorTypes)
        if (t.symbol == symbol)
            return &t;
    return nullptr;
}

std::string_view sensor_type_symbols()
{
    return "S, SR, SP, SC, SR20, M, GD, GE, GF, G605S, G775S, SC500, G955S, SR77, SD, R20ME, "
           "SR2, SCD, SRC, SR36M, SR36ME, SR50M, SR50ME, G1045S, G1395S, MD, G935M, SHL20, SCT";
}

} // namespace rigsim::mcs
