#pragma once
// Bytes as hex text for tests: "05 00 00 00 50 01" <-> the bytes, upper case, space-separated.

#include <sstream>
#include <string>
#include <string_view>

namespace rigsim::test {

/// "05 00 00 00 50 01" -> bytes.
inline std::string bytes(const std::string& hex)
{
    std::istringstream in(hex);
    std::string out;
    unsigned byte = 0;
    while (in >> std::hex >> byte)
        out.push_back(static_cast<char>(byte));
    return out;
}

/// Bytes -> "05 00 00 00 50 01".
inline std::string hex(std::string_view s)
{
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string out;
    for (unsigned char c : s) {
        if (!out.empty())
            out += ' ';
        out += kHex[c >> 4];
        out += kHex[c & 0xf];
    }
    return out;
}

} // namespace rigsim::test
