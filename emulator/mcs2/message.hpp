#pragma once
// The syntax of one MCS2 ASCII message (SmarAct MCS2 Programmer's Guide 1.0.6, 6.2): commands
// separated by ';', each a common command (`*IDN?`) or an instrument command, a path of keywords
// joined by ':' (`:CHANnel0:VELocity`), a '?' for a query, and after at least one space its
// parameters separated by ','. A keyword may end in an index (`CHAN0`, `MOVE2`, `AOUT1`).
//
// This layer knows no keyword: which keywords exist, their long and short forms, the optional
// ones and where a relative command of a compound message starts (6.2.3) are the command tree's.
// It reports each command's syntax error with the SCPI code of the guide's Table 6.4 (6.7): the
// command is not executed and the error goes to the queue; the other commands of the message are
// read on their own (the guide does not say what a failing command does to the ones after it).
//
// Grammar (the guide's, with the choices marked *):
//   message    = [ws] command { [ws] ';' [ws] command } [ws]
//   command    = common | instrument
//   common     = '*' letters ['?'] [params]
//   instrument = [':'] keyword { ':' keyword } ['?'] [params]     * the first ':' may be left out (6.5.2)
//   keyword    = letter { letter } { digit }                      the digits: the index (6.2.2)
//   params     = ws+ param { [ws] ',' [ws] param }
//   param      = ['+'|'-'] digit { digit } ['.' digit { digit }]  * an integer (int32/int64); a fraction is rounded
//              | '"' { char | '""' } '"'                          * a string; "" is one quote (SCPI)
//              | word                                             * a bare string: no space, ',', ';', '"'
// An empty command (nothing between two ';', or an empty message) is no command.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rigsim::mcs2 {

/// The SCPI error codes of the guide's Table 6.4 (6.7) this layer reports.
enum class ScpiError : std::int32_t {
    None = 0,
    InvalidCharacter = -101,   ///< a character no command has (`:CHAN0:STAT?!`)
    InvalidSeparator = -103,   ///< a separator out of place (`::`, `:CHAN0,`, a ':' at the end)
    DataTypeError = -104,      ///< a parameter of no type (`12ab`)
    ParameterNotAllowed = -108, ///< a parameter where the command takes none (from the controller)
    MissingParameter = -109,   ///< a ',' with nothing after it; a setting without its value
    UndefinedHeader = -113,    ///< no header (`?`, `:`, `* `)
    InvalidStringData = -151,  ///< a string without its closing quote
    QueueOverflow = -350,      ///< the error queue overflowed
    InputBufferOverrun = -363, ///< a message longer than the input buffer
};

/// The guide's text of a SCPI error (only -101's and the empty queue's are given verbatim, 4.1).
std::string_view scpi_error_text(ScpiError e);

/// One keyword of a path: its letters as sent and the index its digits give.
struct Keyword {
    std::string name;                    ///< letters as sent (case kept)
    std::optional<std::int64_t> index;   ///< `CHAN0` -> 0; none without digits
    bool operator==(const Keyword& o) const { return name == o.name && index == o.index; }
};

/// One parameter: an integer or a string (quoted or bare).
struct Param {
    enum class Kind { Integer, String };
    Kind kind = Kind::Integer;
    std::int64_t integer = 0;
    std::string text;   ///< a string's value (quotes removed); an integer's digits as sent
    bool operator==(const Param& o) const { return kind == o.kind && integer == o.integer && text == o.text; }
};

/// One command of a message, read.
struct Command {
    ScpiError error = ScpiError::None;   ///< None: the command below is well formed
    std::size_t error_at = 0;            ///< offset in the message of the character at fault
    bool common = false;                 ///< `*IDN?`: its one keyword in `path`
    bool absolute = false;               ///< begins with ':' (referenced to the root, 6.2.3)
    std::vector<Keyword> path;
    bool query = false;
    std::vector<Param> params;
    std::string_view text;               ///< the command as sent, without the separators
};

/// Most commands a message may hold; the others are read as one error (-103) and not executed.
inline constexpr std::size_t kMaxCommandsPerMessage = 64;
/// Most keywords of a path and parameters of a command (the deepest path of the guide has 6
/// keywords, the longest parameter list, a stream frame, 3 per channel of 12).
inline constexpr std::size_t kMaxKeywords = 16;
inline constexpr std::size_t kMaxParams = 64;

/// The commands of `message` (one line, without its CR LF), in order. Work and memory are linear
/// in the message's length.
std::vector<Command> parse_message(std::string_view message);

} // namespace rigsim::mcs2
