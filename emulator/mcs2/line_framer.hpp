#pragma once
// MCS2 ASCII message framing (SmarAct MCS2 Programmer's Guide 1.0.6, 6.1.1 and 6.3): a message is
// the text up to a line feed; "commands are only executed after the device receives the <NL>
// character", and a carriage return before it belongs to the termination (<CR><LF>, 6.1.1).
//
// Pure and resumable, in the manner of the MCS framer (emulator/mcs/line_framer.hpp): parse()
// consumes input up to and including the end of one message and reports what it found; the
// caller loops until the input is used up. A message longer than the size limit is discarded up
// to its line feed and reported once as Overrun (SCPI -363 "input buffer overrun", 6.7), so a
// 10 MB line with no line feed costs no memory.

#include <cstddef>
#include <string>
#include <string_view>

namespace rigsim::mcs2 {

class LineFramer {
public:
    /// The guide gives no input buffer size; the longest message of its examples is 40 bytes, a
    /// compound query of every channel property about 2 KB.
    static constexpr std::size_t kDefaultMaxLine = 4096;

    enum class Status {
        NeedMore,   ///< all input consumed, no complete message yet
        Line,       ///< `line` holds one message (without its CR LF)
        Overrun,    ///< a message exceeded the size limit and was discarded up to its line feed
    };

    struct Result {
        Status status = Status::NeedMore;
        std::size_t consumed = 0;   ///< bytes of the input used by this call
        std::string_view line;      ///< valid until the next parse() call
    };

    explicit LineFramer(std::size_t max_line = kDefaultMaxLine) : max_line_(max_line) {}

    Result parse(std::string_view in);

    /// Bytes of a message begun but not ended.
    std::size_t buffered() const { return buffer_.size(); }

private:
    std::size_t max_line_;
    std::string buffer_;
    bool discarding_ = false;
    bool line_returned_ = false;
};

} // namespace rigsim::mcs2
