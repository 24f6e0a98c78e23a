#pragma once
// MCS command framing (manual 1.1): a command is ':' <command string> '\n'.
// "Empty strings (i.e. a colon character followed by a line feed character) are ignored.
//  All characters between a line feed and a colon are also ignored."
//
// Pure and resumable, in the manner of Asio's request_parser: parse() consumes input up to
// and including the end of one frame and reports what it found; the caller loops until the
// input is used up. A ':' inside a command starts over (the partial command is reported
// as Interrupted). A command longer than the size limit is discarded up to its '\n' and
// reported once as Oversize, so a 10 MB line with no newline costs no memory.

#include <cstddef>
#include <string>
#include <string_view>

namespace rigsim::mcs {

class LineFramer {
public:
    static constexpr std::size_t kDefaultMaxLine = 256;

    enum class Status {
        NeedMore,      ///< all input consumed, no complete frame yet
        Command,       ///< `line` holds one command string (without ':' and '\n')
        Oversize,      ///< a command exceeded the size limit and was discarded
        Interrupted,   ///< a ':' arrived inside a command; `line` holds the dropped part
    };

    struct Result {
        Status status = Status::NeedMore;
        std::size_t consumed = 0;    ///< bytes of the input used by this call
        std::size_t ignored = 0;     ///< bytes outside any command (between '\n' and ':')
        std::string_view line;       ///< valid until the next parse() call
        /// A Command as it crossed the wire, ':' to '\n', when all of it came in this input
        /// (else empty: its start came in an earlier one); valid as `line` is.
        std::string_view frame;
    };

    explicit LineFramer(std::size_t max_line = kDefaultMaxLine) : max_line_(max_line) {}

    Result parse(std::string_view in);

    /// True while a command has started but not ended.
    bool in_command() const { return state_ != State::Idle; }

private:
    enum class State { Idle, Command, Discarding };

    /// In State::Command: takes the command's bytes of `in` from `i` on (advancing `i`); true
    /// when `r` is complete (a command, an interrupted one), false to go on parsing.
    bool take_command(std::string_view in, std::size_t& i, Result& r);

    State state_ = State::Idle;
    std::size_t max_line_;
    std::string buffer_;
    bool line_returned_ = false;
};

} // namespace rigsim::mcs
