#include "emulator/mcs/line_framer.hpp"

namespace rigsim::mcs {

namespace {

/// The first ':' or '\n' of `in` from `from`, or npos (find_first_of() looks each byte up in
/// the set with a library call).
std::size_t find_colon_or_newline(std::string_view in, std::size_t from)
{
    for (std::size_t i = from; i < in.size(); ++i)
        if (in[i] == ':' || in[i] == '\n')
            return i;
    return std::string_view::npos;
}

} // namespace

bool LineFramer::take_command(std::string_view in, std::size_t& i, Result& r)
{
    const auto end = find_colon_or_newline(in, i);
    const auto stop = end == std::string_view::npos ? in.size() : end;
    const auto piece = in.substr(i, stop - i);
    if (buffer_.size() + piece.size() > max_line_) {
        buffer_.clear();
        state_ = State::Discarding;
        i += piece.size();
        return false;
    }
    if (end == std::string_view::npos) {
        buffer_.append(piece);
        i = in.size();
        return false;
    }
    // Zero-copy when the whole command arrived in this input.
    const bool in_one_input = buffer_.empty();
    const std::string_view line = in_one_input ? piece : std::string_view(buffer_.append(piece));
    i = end + 1;
    if (in[end] == ':') {
        // A new command starts inside this one: report the dropped part.
        state_ = State::Command;
        if (line.empty())
            return false;   // "::" is just a colon among ignored characters
        if (line.data() != buffer_.data())
            buffer_.assign(line);
        r.status = Status::Interrupted;
        r.line = buffer_;
        r.consumed = i;
        line_returned_ = true;   // the next parse() starts a fresh command
        return true;
    }
    state_ = State::Idle;
    if (line.empty())
        return false;   // ":\n" is ignored
    r.status = Status::Command;
    r.line = line;
    if (in_one_input && i >= 2 + line.size() && in[i - 2 - line.size()] == ':')   // its ':' too
        r.frame = in.substr(i - 2 - line.size(), line.size() + 2);
    r.consumed = i;
    line_returned_ = true;
    return true;
}

LineFramer::Result LineFramer::parse(std::string_view in)
{
    if (line_returned_) {   // the last result's line lived in buffer_: it is used now
        buffer_.clear();
        line_returned_ = false;
    }
    Result r;
    std::size_t i = 0;
    while (i < in.size()) {
        switch (state_) {
        case State::Idle: {
            const auto colon = in.find(':', i);
            if (colon == std::string_view::npos) {
                r.ignored += in.size() - i;
                i = in.size();
                break;
            }
            r.ignored += colon - i;
            i = colon + 1;
            state_ = State::Command;
            buffer_.clear();
            break;
        }
        case State::Command:
            if (take_command(in, i, r))
                return r;
            break;
        case State::Discarding: {
            const auto end = find_colon_or_newline(in, i);
            if (end == std::string_view::npos) {
                i = in.size();
                break;
            }
            state_ = in[end] == ':' ? State::Command : State::Idle;
            buffer_.clear();
            r.status = Status::Oversize;
            r.consumed = end + 1;
            return r;
        }
        }
    }
    r.consumed = in.size();
    return r;
}

} // namespace rigsim::mcs
