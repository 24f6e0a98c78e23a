#include "emulator/apt/codec.hpp"

namespace rigsim::apt::msg {

namespace {

/// Reads the fields of a data packet in wire order (the caller checked the length).
struct Reader {
    std::string_view in;
    std::size_t pos = 0;

    void get(std::uint8_t& v) { v = get_u8(in, pos++); }
    void get(std::uint16_t& v) { v = get_u16(in, pos), pos += 2; }
    void get(std::int16_t& v) { v = get_i16(in, pos), pos += 2; }
    void get(std::uint32_t& v) { v = get_u32(in, pos), pos += 4; }
    void get(std::int32_t& v) { v = get_i32(in, pos), pos += 4; }
    template <std::size_t N> void get(std::array<char, N>& v)
    {
        in.copy(v.data(), N, pos);
        pos += N;
    }
    void get(std::optional<std::int32_t>& v)
    {
        std::int32_t d = 0;
        get(d);
        v = d;
    }
    void get(MotorStatus& v)
    {
        DcStatus s;
        std::apply([&](auto&... f) { (get(f), ...); }, DcStatus::fields(s));
        v = s;
    }
};

/// The data packet length of message T in its long form.
template <class T> std::size_t data_size()
{
    if constexpr (std::is_same_v<T, MoveRelative> || std::is_same_v<T, MoveAbsolute>)
        return encode_data(T{1, 0}).size();
    else
        return encode_data(T{}).size();
}

Message untyped(const Frame& f)
{
    return Untyped{f.id, f.param1, f.param2, f.has_data, std::string(f.data)};
}

/// The block of sub-message `sub` read from `data` (the bytes after the SubMsgID): nullopt for
/// an ID no block has, or data short of its block's fields (a longer one's tail is ignored).
template <class... Blocks> std::optional<PzmotBlock> read_block(std::uint16_t sub, std::string_view data,
                                                               const std::variant<Blocks...>*)
{
    std::optional<PzmotBlock> out;
    (
        [&] {
            if (out || Blocks::sub_id != sub)
                return;
            Blocks b{};
            if (data.size() < encode_data(b).size())
                return;
            Reader r{data};
            std::apply([&](auto&... field) { (r.get(field), ...); }, Blocks::fields(b));
            out = b;
        }(),
        ...);
    return out;
}

/// Whether message T carries a PZMOT sub-message block (PZMOT_SET_PARAMS, PZMOT_GET_PARAMS).
template <class T> constexpr bool kCarriesBlock = std::is_same_v<T, PzmotSetParams> || std::is_same_v<T, PzmotGetParams>;

/// Frame `f` as message T, a message that carries a block: the first data word names the block
/// (issue 37 p. 371); an unknown one, or a block short of its fields, is untyped.
template <class T> Message as_block(const Frame& f)
{
    if (!f.has_data || f.data.size() < 2)
        return untyped(f);
    auto block = read_block(get_u16(f.data, 0), std::string_view(f.data).substr(2), static_cast<const PzmotBlock*>(nullptr));
    if (!block)
        return untyped(f);
    T m{};
    m.block = std::move(*block);
    return m;
}

/// Frame `f` as message T: from its data packet, or from param1 and param2 of its header.
template <class T> Message as(const Frame& f)
{
    T m{};
    if constexpr (std::is_same_v<T, MoveRelative> || std::is_same_v<T, MoveAbsolute>) {
        if (!f.has_data) {
            m.chan_ident = f.param1;
            return m;
        }
    } else if constexpr (T::header_only) {
        if (f.has_data)
            return untyped(f);
        const std::uint8_t params[2] = {f.param1, f.param2};
        std::size_t i = 0;
        std::apply([&](auto&... field) { ((field = params[i++]), ...); }, T::fields(m));
        return m;
    }
    if (!f.has_data)
        return untyped(f);
    // A packet of another length than the struct's (the header's length is framed, whatever the
    // table says): bytes past the struct are ignored; a shorter one that still holds the fields
    // some unit reads (messages.hpp fields_length) has its reserved tail read as zeros.
    const std::size_t size = data_size<T>();
    const MessageInfo* info = find_message(T::id);
    if (f.data.size() < (info ? info->min_data_length() : size))
        return untyped(f);
    std::string padded;
    std::string_view data = f.data;
    if (data.size() < size) {
        padded.assign(data);
        padded.resize(size, '\0');
        data = padded;
    }
    Reader r{data};
    std::apply([&](auto&... field) { (r.get(field), ...); }, T::fields(m));
    return m;
}

/// Decodes a frame whose ID is its message's.
using Decoder = Message (*)(const Frame&);
/// Above the highest ID of the message table (MGMSG_PZMOT_ACK_STATUSUPDATE, 0x08E2).
constexpr std::size_t kDecoderSlots = 0x0900;
using DecoderTable = std::array<Decoder, kDecoderSlots>;

template <class T> constexpr Decoder decoder_of()
{
    if constexpr (kCarriesBlock<T>)
        return &as_block<T>;
    else
        return &as<T>;
}

template <class... T> constexpr void add_decoders(DecoderTable& table, const std::variant<T...>*)
{
    ((T::id < kDecoderSlots && table[T::id] == nullptr ? void(table[T::id] = decoder_of<T>())
                                                        : throw "two messages share an ID, or one is past the table"),
     ...);
}

/// as<T> of every message of every chapter, indexed by its ID (nullptr: not typed).
template <class... Group> constexpr DecoderTable decoders(const std::tuple<Group...>*)
{
    DecoderTable table{};
    (add_decoders(table, static_cast<const typename Group::variant*>(nullptr)), ...);
    return table;
}

constexpr DecoderTable kDecoders = decoders(static_cast<const Chapters*>(nullptr));

} // namespace

Message decode(const Frame& f)
{
    const Decoder typed = f.id < kDecoderSlots ? kDecoders[f.id] : nullptr;
    return typed ? typed(f) : untyped(f);
}

std::string encode(const Message& m, std::uint8_t dest, std::uint8_t source)
{
    return msg::visit([&](const auto& typed) { return encode(typed, dest, source); }, m);
}

std::uint16_t message_id(const Message& m)
{
    return msg::visit(
        [](const auto& typed) -> std::uint16_t {
            if constexpr (std::is_same_v<std::decay_t<decltype(typed)>, Untyped>)
                return typed.id;
            else
                return std::decay_t<decltype(typed)>::id;
        },
        m);
}

} // namespace rigsim::apt::msg
