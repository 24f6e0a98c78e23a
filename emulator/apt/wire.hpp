#pragma once
// APT wire format (manual sections 3, 4 and 6): a 6-byte header, then for some messages a
// data packet. Every multi-byte field is little-endian: section 6 says "Intel (big-endian)",
// but Intel order is little-endian and every example is (ERRATA).
//
//   header-only:  id_lo id_hi param1 param2 dest        source
//   with data:    id_lo id_hi len_lo len_hi dest|0x80   source   data[len]

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace rigsim::apt {

inline constexpr std::size_t kHeaderSize = 6;
/// Section 4: "although this is a 2-byte long field, currently no datapacket exceeds 255 bytes".
inline constexpr std::size_t kMaxDataLength = 255;
inline constexpr std::size_t kMaxFrameSize = kHeaderSize + kMaxDataLength;
/// Section 4: the MSB of the destination byte says a data packet follows.
inline constexpr std::uint8_t kDataFlag = 0x80;

// Source and destination addresses (section 4, page 10).
inline constexpr std::uint8_t kHost = 0x01;         ///< host controller (the control PC)
inline constexpr std::uint8_t kRack = 0x11;         ///< rack controller, motherboard, comms router
inline constexpr std::uint8_t kBay0 = 0x21;         ///< bay 0 of a card-slot system; bay n is 0x21 + n
inline constexpr std::uint8_t kBay9 = 0x2A;         ///< the last bay
inline constexpr std::uint8_t kGenericUsb = 0x50;   ///< generic USB hardware unit

/// Chan Ident of channel 1, the one channel a single unit or a rack's bay answers for.
inline constexpr std::uint16_t kChan1 = 0x01;

/// True for the addresses of section 4 (without the data flag).
constexpr bool is_valid_address(std::uint8_t a)
{
    return a == kHost || a == kRack || (a >= kBay0 && a <= kBay9) || a == kGenericUsb;
}

// ---- Little-endian fields appended to a message ----

inline void put_u8(std::string& out, std::uint8_t v) { out.push_back(static_cast<char>(v)); }

inline void put_u16(std::string& out, std::uint16_t v)
{
    const char bytes[2] = {static_cast<char>(v & 0xFF), static_cast<char>(v >> 8)};
    out.append(bytes, 2);
}

inline void put_i16(std::string& out, std::int16_t v) { put_u16(out, static_cast<std::uint16_t>(v)); }

inline void put_u32(std::string& out, std::uint32_t v)
{
    const char bytes[4] = {static_cast<char>(v & 0xFF), static_cast<char>((v >> 8) & 0xFF),
                           static_cast<char>((v >> 16) & 0xFF), static_cast<char>(v >> 24)};
    out.append(bytes, 4);
}

inline void put_i32(std::string& out, std::int32_t v) { put_u32(out, static_cast<std::uint32_t>(v)); }

// ---- Little-endian fields read at an offset (the caller checks the length first) ----

inline std::uint8_t get_u8(std::string_view in, std::size_t offset)
{
    assert(offset < in.size());
    return static_cast<std::uint8_t>(in[offset]);
}

inline std::uint16_t get_u16(std::string_view in, std::size_t offset)
{
    assert(offset + 2 <= in.size());
    return static_cast<std::uint16_t>(get_u8(in, offset) | (get_u8(in, offset + 1) << 8));
}

inline std::int16_t get_i16(std::string_view in, std::size_t offset)
{
    return static_cast<std::int16_t>(get_u16(in, offset));
}

inline std::uint32_t get_u32(std::string_view in, std::size_t offset)
{
    assert(offset + 4 <= in.size());
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i)
        v |= static_cast<std::uint32_t>(get_u8(in, offset + i)) << (8 * i);
    return v;
}

inline std::int32_t get_i32(std::string_view in, std::size_t offset)
{
    return static_cast<std::int32_t>(get_u32(in, offset));
}

// ---- Whole messages ----

/// A 6-byte header-only message; `dest` without the data flag.
inline std::string encode_header_only(std::uint16_t id, std::uint8_t param1, std::uint8_t param2,
                                      std::uint8_t dest, std::uint8_t source)
{
    assert((dest & kDataFlag) == 0);
    std::string out;
    out.reserve(kHeaderSize);
    put_u16(out, id);
    put_u8(out, param1);
    put_u8(out, param2);
    put_u8(out, dest);
    put_u8(out, source);
    return out;
}

/// A header with the data flag and the packet's length, then the packet; `dest` without the flag.
inline std::string encode_with_data(std::uint16_t id, std::uint8_t dest, std::uint8_t source,
                                    std::string_view data)
{
    assert((dest & kDataFlag) == 0);
    assert(data.size() <= kMaxDataLength);
    std::string out;
    out.reserve(kHeaderSize + data.size());
    put_u16(out, id);
    put_u16(out, static_cast<std::uint16_t>(data.size()));
    put_u8(out, static_cast<std::uint8_t>(dest | kDataFlag));
    put_u8(out, source);
    out.append(data);
    return out;
}

} // namespace rigsim::apt
