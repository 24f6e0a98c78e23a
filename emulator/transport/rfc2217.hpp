#pragma once
// A serial port over TCP as RFC 2217 ("Telnet Com Port Control Option") has it: the client's
// serial data travels as Telnet data (0xFF doubled), and the port's settings (baud rate, data
// bits, parity, stop bits, flow control, DTR, RTS, BREAK) and its modem and line states travel
// as Telnet subnegotiations of option 44, each setting acknowledged with its value as the port
// now has it (RFC 2217, "Com Port Configuration Commands"). This codec is the access server's
// side, without a socket: bytes from the client in, the serial data for the unit and the
// server's answers out. It negotiates BINARY (RFC 856), SUPPRESS-GO-AHEAD (RFC 858) and
// COM-PORT-OPTION (RFC 2217) both ways, refuses every other option (ECHO included: the unit does
// not echo), answers a request only when it changes the option's state (RFC 854: no
// acknowledgement loops), and ignores, with a note, a subnegotiation it cannot read (a value of
// the wrong length, an unknown command, one longer than kMaxSubnegotiation bytes).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim {

/// The port's settings as the client set them over RFC 2217; each starts as the unit's line has it.
struct SerialSettings {
    std::uint32_t baud = 0;         ///< bits per second
    std::uint8_t data_bits = 8;     ///< 5..8
    std::uint8_t parity = 1;        ///< RFC 2217's codes: 1 none, 2 odd, 3 even, 4 mark, 5 space
    std::uint8_t stop_bits = 1;     ///< RFC 2217's codes: 1 one, 2 two, 3 one and a half
    std::uint8_t flow = 1;          ///< SET-CONTROL's: 1 none, 2 XON/XOFF, 3 hardware, 17 DCD, 19 DSR
    std::uint8_t inbound_flow = 14; ///< 14 none, 15 XON/XOFF, 16 hardware, 18 DTR
    bool dtr = true;                ///< asserted when the port opens, as a pty's are
    bool rts = true;
    bool brk = false;               ///< BREAK on the line
};

class Rfc2217Codec {
public:
    /// What one read of the client's bytes gives.
    struct Out {
        std::string reply;                 ///< the server's answers, for the client
        std::string data;                  ///< the client's serial data, for the unit
        std::vector<std::string> notes;    ///< what the client sent that the server ignored
        bool line_changed = false;         ///< the baud rate, data bits, parity or stop bits changed
    };

    /// Telnet's interpret-as-command and the option of RFC 2217.
    static constexpr std::uint8_t kIac = 255;
    static constexpr std::uint8_t kComPortOption = 44;
    /// A subnegotiation longer than this is no RFC 2217 command: it is dropped.
    static constexpr std::size_t kMaxSubnegotiation = 64;
    /// The modem lines the server reports: CTS, DSR and CD asserted (no modem lines to read on
    /// a unit's emulated port, as rigsim's pty shim reports them).
    static constexpr std::uint8_t kModemState = 0x10 | 0x20 | 0x80;
    /// The line state the server reports: both transmit registers empty.
    static constexpr std::uint8_t kLineState = 0x20 | 0x40;

    /// `unit_baud`: the unit's line rate, the port's until the client sets another (0: 9600).
    explicit Rfc2217Codec(std::uint32_t unit_baud);

    /// Reads `bytes` from the client, appending to `out`.
    void receive(std::string_view bytes, Out& out);
    /// The unit's bytes as Telnet data: 0xFF doubled.
    static std::string escape(std::string_view data);

    const SerialSettings& settings() const { return settings_; }
    /// The client asked the server to hold its data (FLOWCONTROL-SUSPEND) and has not resumed.
    bool suspended() const { return suspended_; }
    /// PURGE-DATA asked to drop the data the server holds for the client (1 or 3), cleared on read.
    bool take_purge_request();

private:
    enum class State {
        Data,
        Iac,          ///< after IAC
        Option,       ///< after IAC WILL/WONT/DO/DONT: the option byte
        Sub,          ///< inside IAC SB ... IAC SE
        SubIac,       ///< IAC inside a subnegotiation
    };

    void negotiate(std::uint8_t verb, std::uint8_t option, Out& out);
    void subnegotiation(Out& out);
    void com_port(std::uint8_t command, std::string_view value, Out& out);
    /// SET-BAUDRATE: 4 bytes, big-endian; 0 asks.
    void set_baud(std::string_view value, Out& out);
    /// SET-DATASIZE, SET-PARITY, SET-STOPSIZE: set within RFC 2217's range, acknowledged.
    void line_setting(std::uint8_t command, std::uint8_t value, Out& out);
    void set_control(std::uint8_t value, Out& out);
    /// IAC SB COM-PORT-OPTION `command` `value` IAC SE, the value's 0xFF doubled.
    static void send(Out& out, std::uint8_t command, std::string_view value);
    static void send(Out& out, std::uint8_t command, std::uint8_t value);
    /// RFC 2217's command became active: the modem state, once, as RFC 2217 servers do.
    void enabled(Out& out);

    SerialSettings settings_;
    State state_ = State::Data;
    std::uint8_t verb_ = 0;
    std::string sub_;
    bool sub_overflow_ = false;
    bool us_[256] = {};     ///< options the server has on its side (WILL acknowledged)
    bool them_[256] = {};   ///< options the client has on its side (DO sent)
    bool announced_ = false;
    bool suspended_ = false;
    bool purge_ = false;
    std::uint8_t linestate_mask_ = 0;
    std::uint8_t modemstate_mask_ = 255;
};

} // namespace rigsim
