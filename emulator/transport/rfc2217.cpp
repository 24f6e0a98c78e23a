#include "emulator/transport/rfc2217.hpp"

#include <string>

namespace rigsim {
namespace {

// Telnet (RFC 854) and its options.
constexpr std::uint8_t kSe = 240;
constexpr std::uint8_t kSb = 250;
constexpr std::uint8_t kWill = 251;
constexpr std::uint8_t kWont = 252;
constexpr std::uint8_t kDo = 253;
constexpr std::uint8_t kDont = 254;
constexpr std::uint8_t kBinary = 0;
constexpr std::uint8_t kSuppressGoAhead = 3;

/// The server's answer to a client command is the command + 100 (RFC 2217).
constexpr std::uint8_t kServer = 100;
// The client's commands.
constexpr std::uint8_t kSignature = 0;
constexpr std::uint8_t kSetBaudRate = 1;
constexpr std::uint8_t kSetDataSize = 2;
constexpr std::uint8_t kSetParity = 3;
constexpr std::uint8_t kSetStopSize = 4;
constexpr std::uint8_t kSetControl = 5;
constexpr std::uint8_t kNotifyLineState = 6;
constexpr std::uint8_t kNotifyModemState = 7;
constexpr std::uint8_t kFlowControlSuspend = 8;
constexpr std::uint8_t kFlowControlResume = 9;
constexpr std::uint8_t kSetLineStateMask = 10;
constexpr std::uint8_t kSetModemStateMask = 11;
constexpr std::uint8_t kPurgeData = 12;

constexpr std::string_view kServerSignature = "rigsim";

bool supported(std::uint8_t option)
{
    return option == kBinary || option == kSuppressGoAhead || option == Rfc2217Codec::kComPortOption;
}

std::string hex_byte(std::uint8_t b)
{
    static constexpr char kDigits[] = "0123456789abcdef";
    return std::string("0x") + kDigits[b >> 4] + kDigits[b & 15];
}

} // namespace

Rfc2217Codec::Rfc2217Codec(std::uint32_t unit_baud)
{
    settings_.baud = unit_baud != 0 ? unit_baud : 9600;
}

std::string Rfc2217Codec::escape(std::string_view data)
{
    std::string out;
    out.reserve(data.size());
    for (const char c : data) {
        out.push_back(c);
        if (static_cast<std::uint8_t>(c) == kIac)
            out.push_back(c);
    }
    return out;
}

bool Rfc2217Codec::take_purge_request()
{
    const bool p = purge_;
    purge_ = false;
    return p;
}

void Rfc2217Codec::receive(std::string_view bytes, Out& out)
{
    for (const char c : bytes) {
        const auto b = static_cast<std::uint8_t>(c);
        switch (state_) {
        case State::Data:
            if (b == kIac)
                state_ = State::Iac;
            else
                out.data.push_back(c);
            break;
        case State::Iac:
            if (b == kIac) {   // a data byte 0xFF
                out.data.push_back(c);
                state_ = State::Data;
            } else if (b == kWill || b == kWont || b == kDo || b == kDont) {
                verb_ = b;
                state_ = State::Option;
            } else if (b == kSb) {
                sub_.clear();
                sub_overflow_ = false;
                state_ = State::Sub;
            } else {
                // NOP, Go-Ahead, Break, Interrupt Process, ...: nothing a serial port does here.
                state_ = State::Data;
            }
            break;
        case State::Option:
            negotiate(verb_, b, out);
            state_ = State::Data;
            break;
        case State::Sub:
            if (b == kIac) {
                state_ = State::SubIac;
            } else if (sub_.size() < kMaxSubnegotiation) {
                sub_.push_back(c);
            } else {
                sub_overflow_ = true;
            }
            break;
        case State::SubIac:
            if (b == kIac) {   // a doubled 0xFF in the value
                if (sub_.size() < kMaxSubnegotiation)
                    sub_.push_back(c);
                else
                    sub_overflow_ = true;
                state_ = State::Sub;
            } else if (b == kSe) {
                subnegotiation(out);
                state_ = State::Data;
            } else {
                // RFC 854: IAC in a subnegotiation is IAC IAC or IAC SE; anything else ends it
                // unread.
                out.notes.push_back("IAC " + hex_byte(b) + " inside a subnegotiation: the subnegotiation is dropped");
                state_ = State::Data;
            }
            break;
        }
    }
}

void Rfc2217Codec::negotiate(std::uint8_t verb, std::uint8_t option, Out& out)
{
    const auto answer = [&](std::uint8_t v) {
        out.reply.push_back(static_cast<char>(kIac));
        out.reply.push_back(static_cast<char>(v));
        out.reply.push_back(static_cast<char>(option));
    };
    switch (verb) {
    case kWill:   // the client offers to enable the option on its side
        if (!supported(option)) {
            answer(kDont);
        } else if (!them_[option]) {
            them_[option] = true;
            answer(kDo);
        }
        break;
    case kWont:
        if (them_[option]) {
            them_[option] = false;
            answer(kDont);
        }
        break;
    case kDo:     // the client asks the server to enable the option on its side
        if (!supported(option)) {
            answer(kWont);
        } else if (!us_[option]) {
            us_[option] = true;
            answer(kWill);
        }
        break;
    case kDont:
        if (us_[option]) {
            us_[option] = false;
            answer(kWont);
        }
        break;
    default:
        break;
    }
    if (option == kComPortOption && (us_[option] || them_[option]))
        enabled(out);
}

void Rfc2217Codec::enabled(Out& out)
{
    if (announced_)
        return;
    announced_ = true;
    send(out, kNotifyModemState + kServer, static_cast<std::uint8_t>(kModemState & modemstate_mask_));
}

void Rfc2217Codec::send(Out& out, std::uint8_t command, std::string_view value)
{
    out.reply.push_back(static_cast<char>(kIac));
    out.reply.push_back(static_cast<char>(kSb));
    out.reply.push_back(static_cast<char>(kComPortOption));
    out.reply.push_back(static_cast<char>(command));
    out.reply += escape(value);
    out.reply.push_back(static_cast<char>(kIac));
    out.reply.push_back(static_cast<char>(kSe));
}

void Rfc2217Codec::send(Out& out, std::uint8_t command, std::uint8_t value)
{
    const char c = static_cast<char>(value);
    send(out, command, std::string_view(&c, 1));
}

void Rfc2217Codec::subnegotiation(Out& out)
{
    if (sub_overflow_) {
        out.notes.push_back("a subnegotiation longer than " + std::to_string(kMaxSubnegotiation) + " bytes: dropped");
        return;
    }
    if (sub_.empty()) {
        out.notes.push_back("an empty subnegotiation: ignored");
        return;
    }
    if (static_cast<std::uint8_t>(sub_[0]) != kComPortOption) {
        out.notes.push_back("a subnegotiation of option " + std::to_string(static_cast<std::uint8_t>(sub_[0]))
                            + ", not COM-PORT-OPTION (44): ignored");
        return;
    }
    if (sub_.size() < 2) {
        out.notes.push_back("COM-PORT-OPTION without a command: ignored");
        return;
    }
    com_port(static_cast<std::uint8_t>(sub_[1]), std::string_view(sub_).substr(2), out);
}

void Rfc2217Codec::com_port(std::uint8_t command, std::string_view value, Out& out)
{
    const auto one_byte = [&](const char* name) {
        if (value.size() == 1)
            return true;
        out.notes.push_back(std::string(name) + " with " + std::to_string(value.size()) + " value bytes, not 1: ignored");
        return false;
    };
    const auto byte = value.empty() ? std::uint8_t{0} : static_cast<std::uint8_t>(value[0]);
    switch (command) {
    case kSignature:
        // An empty value asks for the server's; the client's own is taken as said.
        if (value.empty())
            send(out, kSignature + kServer, kServerSignature);
        return;
    case kSetBaudRate:
        set_baud(value, out);
        return;
    case kSetDataSize:
    case kSetParity:
    case kSetStopSize:
        if (one_byte(command == kSetDataSize ? "SET-DATASIZE" : command == kSetParity ? "SET-PARITY" : "SET-STOPSIZE"))
            line_setting(command, byte, out);
        return;
    case kSetControl:
        if (one_byte("SET-CONTROL"))
            set_control(byte, out);
        return;
    case kNotifyLineState:   // a client's poll: the state now
        send(out, kNotifyLineState + kServer, static_cast<std::uint8_t>(kLineState & linestate_mask_));
        return;
    case kNotifyModemState:
        send(out, kNotifyModemState + kServer, static_cast<std::uint8_t>(kModemState & modemstate_mask_));
        return;
    case kFlowControlSuspend:
        suspended_ = true;
        return;
    case kFlowControlResume:
        suspended_ = false;
        return;
    case kSetLineStateMask:
        if (!one_byte("SET-LINESTATE-MASK"))
            return;
        linestate_mask_ = byte;
        send(out, kSetLineStateMask + kServer, byte);
        return;
    case kSetModemStateMask:
        if (!one_byte("SET-MODEMSTATE-MASK"))
            return;
        modemstate_mask_ = byte;
        send(out, kSetModemStateMask + kServer, byte);
        return;
    case kPurgeData:
        if (!one_byte("PURGE-DATA"))
            return;
        if (byte < 1 || byte > 3) {
            out.notes.push_back("PURGE-DATA " + std::to_string(byte) + " (1..3): ignored");
            return;
        }
        // 1: the data the server received from the unit and holds for the client; 2: what it
        // holds for the unit (nothing: it passes on at once).
        purge_ = purge_ || byte != 2;
        send(out, kPurgeData + kServer, byte);
        return;
    default:
        out.notes.push_back("COM-PORT-OPTION command " + std::to_string(command) + " (0..12): ignored");
        return;
    }
}

void Rfc2217Codec::set_baud(std::string_view value, Out& out)
{
    if (value.size() != 4) {
        out.notes.push_back("SET-BAUDRATE with " + std::to_string(value.size()) + " value bytes, not 4: ignored");
        return;
    }
    std::uint32_t baud = 0;
    for (const char c : value)
        baud = baud << 8 | static_cast<std::uint8_t>(c);
    if (baud != 0 && baud != settings_.baud) {   // 0 asks for the current rate
        settings_.baud = baud;
        out.line_changed = true;
    }
    const std::uint32_t b = settings_.baud;
    const char be[4] = {static_cast<char>(b >> 24), static_cast<char>(b >> 16), static_cast<char>(b >> 8),
                        static_cast<char>(b)};
    send(out, kSetBaudRate + kServer, std::string_view(be, 4));
}

void Rfc2217Codec::line_setting(std::uint8_t command, std::uint8_t value, Out& out)
{
    // Each: its name, its field, its range and what stays when a value is out of it.
    struct Setting {
        const char* name;
        std::uint8_t SerialSettings::*field;
        std::uint8_t lo;
        std::uint8_t hi;
        const char* stays;
    };
    static constexpr Setting kSettings[] = {
        {"SET-DATASIZE", &SerialSettings::data_bits, 5, 8, "the size stays"},
        {"SET-PARITY", &SerialSettings::parity, 1, 5, "the parity stays"},
        {"SET-STOPSIZE", &SerialSettings::stop_bits, 1, 3, "the stop bits stay"},
    };
    const auto& s = kSettings[command - kSetDataSize];
    auto& field = settings_.*s.field;
    if (value >= s.lo && value <= s.hi && value != field) {
        field = value;
        out.line_changed = true;
    } else if (value != 0 && (value < s.lo || value > s.hi)) {   // 0 asks for the current value
        out.notes.push_back(std::string(s.name) + " " + std::to_string(value) + " (" + std::to_string(s.lo) + ".."
                            + std::to_string(s.hi) + "): " + s.stays);
    }
    send(out, command + kServer, field);
}

void Rfc2217Codec::set_control(std::uint8_t value, Out& out)
{
    std::uint8_t answer = value;
    switch (value) {
    case 0:   // the outbound flow control now
        answer = settings_.flow;
        break;
    case 1:
    case 2:
    case 3:
    case 17:
    case 19:
        settings_.flow = value;
        break;
    case 4:
        answer = settings_.brk ? 5 : 6;
        break;
    case 5:
    case 6:
        settings_.brk = value == 5;
        break;
    case 7:
        answer = settings_.dtr ? 8 : 9;
        break;
    case 8:
    case 9:
        settings_.dtr = value == 8;
        break;
    case 10:
        answer = settings_.rts ? 11 : 12;
        break;
    case 11:
    case 12:
        settings_.rts = value == 11;
        break;
    case 13:
        answer = settings_.inbound_flow;
        break;
    case 14:
    case 15:
    case 16:
    case 18:
        settings_.inbound_flow = value;
        break;
    default:
        out.notes.push_back("SET-CONTROL " + std::to_string(value) + " (0..19): ignored");
        return;
    }
    send(out, kSetControl + kServer, answer);
}

} // namespace rigsim
