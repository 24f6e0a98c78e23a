#include "emulator/mcs2/line_framer.hpp"

namespace rigsim::mcs2 {

LineFramer::Result LineFramer::parse(std::string_view in)
{
    if (line_returned_) {   // the last Line's text lived in buffer_ until this call
        buffer_.clear();
        line_returned_ = false;
    }
    Result r;
    const auto lf = in.find('\n');
    const std::size_t take = lf == std::string_view::npos ? in.size() : lf + 1;
    r.consumed = take;
    if (!discarding_) {
        const std::size_t body = lf == std::string_view::npos ? take : lf;
        if (buffer_.size() + body > max_line_) {
            discarding_ = true;
            buffer_.clear();
        } else {
            buffer_.append(in.data(), body);
        }
    }
    if (lf == std::string_view::npos)
        return r;   // NeedMore
    if (discarding_) {
        discarding_ = false;
        r.status = Status::Overrun;
        return r;
    }
    if (!buffer_.empty() && buffer_.back() == '\r')
        buffer_.pop_back();   // <CR><LF> (6.1.1)
    r.status = Status::Line;
    r.line = buffer_;
    line_returned_ = true;
    return r;
}

} // namespace rigsim::mcs2
