#include "emulator/apt/messages.hpp"

#include <array>
#include <limits>

namespace rigsim::apt {

namespace {

constexpr std::int16_t H = -1;   // header-only
constexpr Group G = Group::Generic;
constexpr Group M = Group::Motor;
constexpr Group P = Group::Piezo;
constexpr Group S = Group::StrainGauge;

// One entry per line of messages.def; the name is the constant's own spelling, so it can never
// drift from its ID.
constexpr MessageInfo kTable[] = {
#define RIGSIM_APT_TABLE(NAME, ID, LENGTH, CHAPTER, LISTS) {NAME, std::string_view(#NAME), LENGTH, CHAPTER},
#define RIGSIM_APT_TABLE_SHORT_FORM_TOO(NAME, ID, LENGTH, CHAPTER, LISTS)                                             \
    {NAME, std::string_view(#NAME), LENGTH, CHAPTER, true},
#define RIGSIM_APT_TABLE_LATER(NAME, ID, LENGTH, CHAPTER, FIELDS, LISTS)                                              \
    {NAME, std::string_view(#NAME), LENGTH, CHAPTER, false, true, FIELDS},
#include "emulator/apt/messages.def"
#undef RIGSIM_APT_TABLE
#undef RIGSIM_APT_TABLE_SHORT_FORM_TOO
#undef RIGSIM_APT_TABLE_LATER
};

constexpr std::size_t kTableSize = sizeof(kTable) / sizeof(kTable[0]);
static_assert(kTableSize < std::numeric_limits<std::uint8_t>::max(),
              "the ID index stores table positions + 1 in a byte");

/// One byte per possible ID: 0 = unknown, else table position + 1. The framer looks up
/// every byte offset while it resyncs, so the lookup is one load.
using IdIndex = std::array<std::uint8_t, 0x10000>;

IdIndex build_index()
{
    IdIndex index{};
    for (std::size_t i = 0; i < kTableSize; ++i)
        index[kTable[i].id] = static_cast<std::uint8_t>(i + 1);
    return index;
}

} // namespace

const MessageInfo* find_message(std::uint16_t id)
{
    static const IdIndex index = build_index();
    const auto slot = index[id];
    return slot == 0 ? nullptr : &kTable[slot - 1];
}

MessageTable all_messages()
{
    return MessageTable{kTable, kTableSize};
}

} // namespace rigsim::apt
