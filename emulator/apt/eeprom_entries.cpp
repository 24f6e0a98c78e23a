#include "emulator/apt/eeprom_entries.hpp"

#include "emulator/core/device.hpp"

#include <cstdio>

namespace rigsim::apt {

/// The manual name of message `id`, or its ID in hex.
std::string message_name(std::uint16_t id)
{
    if (const auto* info = find_message(id))
        return std::string(info->name);
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%04x", id);
    return buf;
}

/// State file key of a saved SET message: "bay0/0x0413".
std::string eeprom_key(std::size_t bay, std::uint16_t id)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string k = "bay" + std::to_string(bay) + "/0x";
    for (int shift = 12; shift >= 0; shift -= 4)
        k += kHex[(id >> shift) & 0xf];
    return k;
}

/// The bay and message of a key exactly as eeprom_key writes it, or nullopt.
std::optional<std::pair<std::size_t, std::uint16_t>> parse_eeprom_key(const std::string& key)
{
    constexpr std::size_t kMaxBayDigits = 3;
    if (key.compare(0, 3, "bay") != 0)
        return std::nullopt;
    std::size_t i = 3;
    std::size_t bay = 0;
    while (i < key.size() && i - 3 < kMaxBayDigits && key[i] >= '0' && key[i] <= '9')
        bay = bay * 10 + static_cast<std::size_t>(key[i++] - '0');
    if (i == 3 || key.compare(i, 3, "/0x") != 0 || key.size() != i + 7)
        return std::nullopt;
    unsigned id = 0;
    for (i += 3; i < key.size(); ++i) {
        const char c = key[i];
        if (c >= '0' && c <= '9')
            id = id * 16 + static_cast<unsigned>(c - '0');
        else if (c >= 'a' && c <= 'f')
            id = id * 16 + static_cast<unsigned>(c - 'a' + 10);
        else
            return std::nullopt;
    }
    const auto parsed = std::make_pair(bay, static_cast<std::uint16_t>(id));
    if (eeprom_key(parsed.first, parsed.second) != key)   // "bay00/...": one spelling per entry
        return std::nullopt;
    return parsed;
}

/// `data` as lower-case hex, two digits a byte.
std::string to_hex(std::string_view data)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (unsigned char c : data) {
        out += kHex[c >> 4];
        out += kHex[c & 0xf];
    }
    return out;
}

/// `hex` (an even number of [0-9a-fA-F]) as bytes in `out`, or false and why not in `why`.
bool from_hex(const std::string& hex, std::string& out, std::string& why)
{
    auto digit = [](char c) {
        if (c >= '0' && c <= '9')
            return c - '0';
        if (c >= 'a' && c <= 'f')
            return c - 'a' + 10;
        if (c >= 'A' && c <= 'F')
            return c - 'A' + 10;
        return -1;
    };
    for (std::size_t i = 0; i < hex.size(); ++i) {
        if (digit(hex[i]) < 0) {
            why = "data is not hex (character " + std::to_string(i + 1) + " is '" + printable(hex.substr(i, 1)) + "')";
            return false;
        }
    }
    if (hex.size() % 2 != 0) {
        why = "data has an odd number of hex digits (" + std::to_string(hex.size()) + ")";
        return false;
    }
    out.clear();
    for (std::size_t i = 0; i < hex.size(); i += 2)
        out.push_back(static_cast<char>(digit(hex[i]) * 16 + digit(hex[i + 1])));
    return true;
}

/// The EEPROMPARAMS message of a unit kind: MOT_ (p. 60) for motor and solenoid units, PZ_
/// (p. 113) for piezo and strain gauge units.
const char* eeprom_message(UnitKind kind)
{
    return kind == UnitKind::Piezo || kind == UnitKind::StrainGauge ? "PZ_SET_EEPROMPARAMS" : "MOT_SET_EEPROMPARAMS";
}

/// The frame a stored SET is replayed as, from the host to `dest`: its data packet, or for a
/// header-only SET its param1 and param2.
Frame saved_frame(const MessageInfo& info, std::uint8_t dest, const std::string& data)
{
    Frame f;
    f.id = info.id;
    f.dest = dest;
    f.source = kHost;
    f.info = &info;
    f.has_data = !info.header_only();
    if (f.has_data) {
        f.data = data;
    } else {
        f.param1 = static_cast<std::uint8_t>(data[0]);
        f.param2 = static_cast<std::uint8_t>(data[1]);
    }
    return f;
}

} // namespace rigsim::apt
