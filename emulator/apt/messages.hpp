#pragma once
// The APT message table (Thorlabs APT protocol, issue 3, 2012): every message of its
// "Generic System Control Messages", "Motor Control Messages" (including the solenoid
// messages, which the manual files under the motor controllers) and "Piezo Control
// Messages" (including the TSG001 strain gauge reader's, which the manual files under the
// piezo controllers); then the motor messages of later protocol issues that later clients
// send (`later_issue`: POWERPARAMS, TRIGGER, the K-Cube blocks, TSTACTUATORTYPE).
// The frame framer checks every header against it, as MAVLink's framer checks its
// message-entry table: an ID the table does not know, or a header-only message with the data
// flag (a data message without it), or a data packet over 255 bytes, is not a frame. A packet
// of another length than the table's layout is one (frame_framer.hpp): a SET as long as the
// fields a unit reads (`fields_length`) is acted on, a missing reserved tail read as zeros and
// bytes past the layout ignored (and noted in the wire log); a shorter one is ignored and logged.
//
// IDs and lengths follow the detailed section of each message, corrected by the errata
// (docs/protocol/errata.md) where that section is itself wrong; every choice made where
// the manual is ambiguous is a comment at the message's line in messages.def, the one place
// that declares a message's ID, name, length, chapter and the takes lists that name it.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace rigsim::apt {

/// The chapter a message belongs to.
enum class Group : std::uint8_t {
    Generic,       ///< MOD_*, HW_*, RACK_*, HUB_* ("Generic System Control Messages")
    Motor,         ///< MOT_* ("Motor Control Messages", "Solenoid Control Messages")
    Piezo,         ///< PZ_* ("Piezo Control Messages") except the strain gauge reader's
    StrainGauge,   ///< PZ_*TSG_* (the TSG001's messages, in "Piezo Control Messages")
};

/// One message of the table.
struct MessageInfo {
    std::uint16_t id;
    std::string_view name;            ///< manual spelling, e.g. "MGMSG_MOT_MOVE_ABSOLUTE"
    std::int16_t data_length;         ///< -1: header-only; else the data packet's length in its layout
    Group group;
    bool header_only_allowed = false; ///< a short header-only form exists beside the data form
    bool later_issue = false;         ///< not in the 2012 manual but in later issues: framed always; acted on
                                      ///< only by units of a later firmware generation (HW_YES/NO_FLASH_PROGRAMMING: all)
    /// The fewest data bytes any unit reads of it: the fields before a reserved tail that
    /// clients leave out (0: all data_length bytes). A unit may read more (Module::fields_read).
    std::int16_t fields_length = 0;

    /// True when the message is a 6-byte header without a data packet (in its only form).
    constexpr bool header_only() const { return data_length < 0; }
    /// The data bytes the codec needs to type the message (fields_length, else data_length).
    constexpr std::size_t min_data_length() const
    {
        return static_cast<std::size_t>(fields_length > 0 ? fields_length : (data_length < 0 ? 0 : data_length));
    }
};

/// The message with this ID, or nullptr when the table does not know it.
const MessageInfo* find_message(std::uint16_t id);

/// The whole table, in the manual's order (generic messages first), then the later issues' motor messages.
struct MessageTable {
    const MessageInfo* first;
    std::size_t count;

    const MessageInfo* begin() const { return first; }
    const MessageInfo* end() const { return first + count; }
    std::size_t size() const { return count; }
    const MessageInfo& operator[](std::size_t i) const { return first[i]; }
};

/// Every message rigsim's APT framer accepts.
MessageTable all_messages();

// The constants, one per line of messages.def, e.g. MGMSG_MOT_MOVE_ABSOLUTE = 0x0453.
#define RIGSIM_APT_TABLE(NAME, ID, LENGTH, CHAPTER, LISTS) constexpr std::uint16_t NAME = ID;
#define RIGSIM_APT_TABLE_SHORT_FORM_TOO(NAME, ID, LENGTH, CHAPTER, LISTS) constexpr std::uint16_t NAME = ID;
#define RIGSIM_APT_TABLE_LATER(NAME, ID, LENGTH, CHAPTER, FIELDS, LISTS) constexpr std::uint16_t NAME = ID;
#include "emulator/apt/messages.def"
#undef RIGSIM_APT_TABLE
#undef RIGSIM_APT_TABLE_SHORT_FORM_TOO
#undef RIGSIM_APT_TABLE_LATER

/// The data packet's length of message `id` in its layout (-1: header-only), as messages.def
/// gives it, at compile time: the codec's structs take their form from it. kNotInTable for an ID
/// the table does not know.
inline constexpr std::int16_t kNotInTable = -2;
constexpr std::int16_t data_length_of(std::uint16_t id)
{
    constexpr std::int16_t H = -1;
    switch (id) {
#define RIGSIM_APT_TABLE(NAME, ID, LENGTH, CHAPTER, LISTS) case ID: return LENGTH;
#define RIGSIM_APT_TABLE_SHORT_FORM_TOO(NAME, ID, LENGTH, CHAPTER, LISTS) case ID: return LENGTH;
#define RIGSIM_APT_TABLE_LATER(NAME, ID, LENGTH, CHAPTER, FIELDS, LISTS) case ID: return LENGTH;
#include "emulator/apt/messages.def"
#undef RIGSIM_APT_TABLE
#undef RIGSIM_APT_TABLE_SHORT_FORM_TOO
#undef RIGSIM_APT_TABLE_LATER
    default:
        return kNotInTable;
    }
}

/// The takes lists a message is on, as bits (messages.def's last column, where each list's source and
/// choices are given): a unit of the manual's cross-reference tables acts on the messages of its
/// model's lists only (ControllerModel::takes and later_takes, catalogue.cpp).
using TakesLists = std::uint16_t;
inline constexpr TakesLists kTsc = 1U << 0;          ///< TSC001, KSC101 (p. 138; D-3, D-4)
inline constexpr TakesLists kTpz = 1U << 1;          ///< TPZ001, KPZ101 (p. 133; D-5)
inline constexpr TakesLists kBpc = 1U << 2;          ///< a BPC301/BPC303 bay (p. 132; D-6)
inline constexpr TakesLists kTsg = 1U << 3;          ///< TSG001, KSG101 (p. 134)
inline constexpr TakesLists kKscLater = 1U << 4;     ///< a KSC101 of the later generation, beyond kTsc
inline constexpr TakesLists kKpzLater = 1U << 5;     ///< a KPZ101 of the later generation, beyond kTpz
inline constexpr TakesLists kKsgLater = 1U << 6;     ///< a KSG101 of the later generation, beyond kTsg
inline constexpr TakesLists kTCubeLater = 1U << 7;   ///< a TPZ001 or TSG001 of the later generation
inline constexpr TakesLists kMff = 1U << 8;          ///< MFF101, MFF102 (issue 37 p. 20)
inline constexpr TakesLists kMpc = 1U << 9;          ///< MPC320, MPC220 (issue 37 p. 29)
inline constexpr TakesLists kPzmot = 1U << 10;       ///< KIM101, TIM101 (issue 37 p. 28-29)
inline constexpr TakesLists kMpz = 1U << 11;         ///< an MMR601's MPZ601 card (issue 37 p. 7)

namespace messages_detail {
/// A message's ID and takes lists, one per line of messages.def.
struct Listed {
    std::uint16_t id;
    TakesLists lists;
};
inline constexpr Listed kListed[] = {
#define RIGSIM_APT_TABLE(NAME, ID, LENGTH, CHAPTER, LISTS) {ID, LISTS},
#define RIGSIM_APT_TABLE_SHORT_FORM_TOO(NAME, ID, LENGTH, CHAPTER, LISTS) {ID, LISTS},
#define RIGSIM_APT_TABLE_LATER(NAME, ID, LENGTH, CHAPTER, FIELDS, LISTS) {ID, LISTS},
#include "emulator/apt/messages.def"
#undef RIGSIM_APT_TABLE
#undef RIGSIM_APT_TABLE_SHORT_FORM_TOO
#undef RIGSIM_APT_TABLE_LATER
};

constexpr std::size_t count_on(TakesLists list)
{
    std::size_t n = 0;
    for (const auto& m : kListed)
        n += (m.lists & list) != 0 ? 1 : 0;
    return n;
}

template <TakesLists List> constexpr std::array<std::uint16_t, count_on(List)> ids_on()
{
    std::array<std::uint16_t, count_on(List)> ids{};
    std::size_t n = 0;
    for (const auto& m : kListed)
        if ((m.lists & List) != 0)
            ids[n++] = m.id;
    return ids;
}
} // namespace messages_detail

/// The IDs of the messages on takes list `List` (one of kTsc, ...), in the table's order, at compile time.
template <TakesLists List> inline constexpr auto kIdsOnList = messages_detail::ids_on<List>();

} // namespace rigsim::apt
