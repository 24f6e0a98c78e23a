#include "emulator/mcs2/positioner_types.hpp"

#include <array>

namespace rigsim::mcs2 {

namespace {

// Table 1.1 of the Positioner Types document, with 302 from its Table 1.2 (the errata: Table 1.1
// lacks it). 316 is named as in Table 1.1; 360 is "S1" (single piezo) as its name says.
constexpr std::array<PositionerType, 31> kTypes{{
    {300, "SL...S1SS", Motion::Linear, 'S', Reference::SingleMark},
    {301, "SL...D1SS", Motion::Linear, 'S', Reference::SingleMark},
    {302, "SL...T1SS", Motion::Linear, 'S', Reference::SingleMark},
    {303, "SL...S1SC1", Motion::Linear, 'S', Reference::DistanceCoded},
    {304, "SL...D1SC1", Motion::Linear, 'S', Reference::DistanceCoded},
    {307, "SL...D1SC2", Motion::Linear, 'S', Reference::DistanceCoded},
    {309, "SR...S1S5S", Motion::Rotary, 'S', Reference::SingleMark},
    {312, "SR...S1S6S", Motion::Rotary, 'S', Reference::SingleMark},
    {313, "SR...D1S6S", Motion::Rotary, 'S', Reference::SingleMark},
    {316, "SR...D1S7S", Motion::Rotary, 'S', Reference::SingleMark},
    {320, "SR...T1S8S", Motion::Rotary, 'S', Reference::SingleMark},
    {325, "SG...D1S1S", Motion::Goniometer, 'S', Reference::SingleMark},
    {328, "SG...D1S2S", Motion::Goniometer, 'S', Reference::SingleMark},
    {342, "SL...S1LE", Motion::Linear, 'L', Reference::EndStop},
    {343, "SL...D1LE", Motion::Linear, 'L', Reference::EndStop},
    {345, "SL...S1LS", Motion::Linear, 'L', Reference::SingleMark},
    {346, "SL...D1LS", Motion::Linear, 'L', Reference::SingleMark},
    {348, "SL...S1LC1", Motion::Linear, 'L', Reference::DistanceCoded},
    {349, "SL...D1LC1", Motion::Linear, 'L', Reference::DistanceCoded},
    {354, "SR...S1L2S", Motion::Rotary, 'L', Reference::SingleMark},
    {355, "SR...D1L2S", Motion::Rotary, 'L', Reference::SingleMark},
    {357, "SL...S1ME", Motion::Linear, 'M', Reference::EndStop},
    {358, "SL...D1ME", Motion::Linear, 'M', Reference::EndStop},
    {360, "SL...S1P1E", Motion::Linear, 'P', Reference::EndStop},
    {361, "SL...D1P1E", Motion::Linear, 'P', Reference::EndStop},
    {363, "SG...S1M1E", Motion::Goniometer, 'M', Reference::EndStop},
    {366, "SG...S1M2E", Motion::Goniometer, 'M', Reference::EndStop},
    {381, "SG...D1L1S", Motion::Goniometer, 'L', Reference::SingleMark},
    {383, "SG...D1L2S", Motion::Goniometer, 'L', Reference::SingleMark},
    {387, "SG...D1L1E", Motion::Goniometer, 'L', Reference::EndStop},
    {389, "SG...D1L2E", Motion::Goniometer, 'L', Reference::EndStop},
}};

} // namespace

const PositionerType* positioner_type(std::int32_t code)
{
    for (const auto& t : kTypes)
        if (t.code == code)
            return &t;
    return nullptr;
}

std::string_view positioner_type_codes()
{
    return "300, 301, 302, 303, 304, 307, 309, 312, 313, 316, 320, 325, 328, 342, 343, 345, 346, 348, 349, 354, "
           "355, 357, 358, 360, 361, 363, 366, 381, 383, 387, 389";
}

} // namespace rigsim::mcs2
