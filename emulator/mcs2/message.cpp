#include "emulator/mcs2/message.hpp"

#include <limits>

namespace rigsim::mcs2 {

namespace {

bool is_letter(char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

bool is_space(char c)
{
    return c == ' ' || c == '\t';
}

/// Reads one command from `text`, which starts at offset `base` of the message.
class CommandReader {
public:
    CommandReader(std::string_view text, std::size_t base) : s_(text), base_(base) { c_.text = text; }

    Command read()
    {
        if (s_[i_] == '*') {
            c_.common = true;
            ++i_;
            if (!keyword(false))
                return std::move(c_);
        } else {
            if (s_[i_] == ':') {
                c_.absolute = true;
                ++i_;
            }
            while (true) {
                if (!keyword(true))
                    return std::move(c_);
                if (i_ < s_.size() && s_[i_] == ':') {
                    ++i_;
                    continue;
                }
                break;
            }
        }
        if (i_ < s_.size() && s_[i_] == '?') {
            c_.query = true;
            ++i_;
        }
        if (i_ == s_.size())
            return std::move(c_);
        if (!is_space(s_[i_]))
            return fail(ScpiError::InvalidCharacter);
        skip_space();
        if (i_ < s_.size())
            params();
        return std::move(c_);
    }

private:
    Command fail(ScpiError e)
    {
        c_.error = e;
        c_.error_at = base_ + i_;
        return c_;
    }
    bool failed(ScpiError e)
    {
        fail(e);
        return false;
    }

    void skip_space()
    {
        while (i_ < s_.size() && is_space(s_[i_]))
            ++i_;
    }

    /// One keyword at i_ into the path; false (and the error set) when there is none.
    bool keyword(bool indexed)
    {
        const std::size_t start = i_;
        while (i_ < s_.size() && is_letter(s_[i_]))
            ++i_;
        if (i_ == start) {
            if (i_ == s_.size() || s_[i_] == '?' || is_space(s_[i_]))
                return failed(c_.path.empty() ? ScpiError::UndefinedHeader : ScpiError::InvalidSeparator);
            return failed(s_[i_] == ':' || s_[i_] == ',' ? ScpiError::InvalidSeparator : ScpiError::InvalidCharacter);
        }
        Keyword k{std::string(s_.substr(start, i_ - start)), std::nullopt};
        const std::size_t digits = i_;
        while (i_ < s_.size() && is_digit(s_[i_]))
            ++i_;
        if (i_ > digits) {
            if (!indexed || i_ - digits > 9)   // an index is a channel or module number
                return failed(ScpiError::InvalidCharacter);
            std::int64_t v = 0;
            for (std::size_t j = digits; j < i_; ++j)
                v = v * 10 + (s_[j] - '0');
            k.index = v;
        }
        if (c_.path.size() == kMaxKeywords)
            return failed(ScpiError::UndefinedHeader);   // no path of the tree is this deep
        c_.path.push_back(std::move(k));
        return true;
    }

    /// The parameters from i_ (not at a space) to the end.
    void params()
    {
        while (true) {
            if (c_.params.size() == kMaxParams) {
                fail(ScpiError::InvalidSeparator);
                return;
            }
            if (!param())
                return;
            skip_space();
            if (i_ == s_.size())
                return;
            if (s_[i_] != ',') {
                fail(ScpiError::InvalidSeparator);
                return;
            }
            ++i_;
            skip_space();
            if (i_ == s_.size()) {
                fail(ScpiError::MissingParameter);
                return;
            }
        }
    }

    bool param()
    {
        Param p;
        const std::size_t start = i_;
        if (s_[i_] == '"') {
            p.kind = Param::Kind::String;
            ++i_;
            while (true) {
                if (i_ == s_.size())
                    return failed(ScpiError::InvalidStringData);
                if (s_[i_] == '"') {
                    if (i_ + 1 < s_.size() && s_[i_ + 1] == '"') {   // "" is one quote
                        p.text += '"';
                        i_ += 2;
                        continue;
                    }
                    ++i_;
                    break;
                }
                p.text += s_[i_++];
            }
            c_.params.push_back(std::move(p));
            return true;
        }
        if (s_[i_] == ',')
            return failed(ScpiError::MissingParameter);
        const bool sign = s_[i_] == '+' || s_[i_] == '-';
        if (is_digit(s_[i_]) || (sign && i_ + 1 < s_.size() && is_digit(s_[i_ + 1]))) {
            const bool negative = s_[i_] == '-';
            if (sign)
                ++i_;
            std::uint64_t v = 0;
            constexpr std::uint64_t kLimit = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) + 1;
            while (i_ < s_.size() && is_digit(s_[i_])) {
                const auto d = static_cast<std::uint64_t>(s_[i_] - '0');
                if (v > (kLimit - d) / 10)
                    return failed(ScpiError::DataTypeError);   // past int64 (checked before it wraps)
                v = v * 10 + d;
                ++i_;
            }
            // A decimal fraction (`:MOVE0 1000000.000000`, as EPICS motorSmarAct prints every value
            // with %f) is taken, rounded to the nearest integer: the properties are integers.
            if (i_ + 1 < s_.size() && s_[i_] == '.' && is_digit(s_[i_ + 1])) {
                const bool round_up = s_[i_ + 1] >= '5';
                ++i_;
                while (i_ < s_.size() && is_digit(s_[i_]))
                    ++i_;
                if (round_up && ++v > kLimit)
                    return failed(ScpiError::DataTypeError);
            }
            if (i_ < s_.size() && !is_space(s_[i_]) && s_[i_] != ',')
                return failed(ScpiError::DataTypeError);   // `12ab`
            if (!negative && v == kLimit)
                return failed(ScpiError::DataTypeError);
            p.integer = negative ? static_cast<std::int64_t>(0 - v) : static_cast<std::int64_t>(v);
            p.text = std::string(s_.substr(start, i_ - start));
            c_.params.push_back(std::move(p));
            return true;
        }
        p.kind = Param::Kind::String;
        while (i_ < s_.size() && !is_space(s_[i_]) && s_[i_] != ',') {
            const auto ch = static_cast<unsigned char>(s_[i_]);
            if (s_[i_] == '"' || ch < 0x20 || ch >= 0x7f)
                return failed(ScpiError::InvalidCharacter);
            ++i_;
        }
        p.text = std::string(s_.substr(start, i_ - start));
        c_.params.push_back(std::move(p));
        return true;
    }

    std::string_view s_;
    std::size_t base_;
    std::size_t i_ = 0;
    Command c_;
};

} // namespace

std::string_view scpi_error_text(ScpiError e)
{
    switch (e) {
    case ScpiError::None:
        return "No Error";
    case ScpiError::InvalidCharacter:
        return "Invalid character";
    case ScpiError::InvalidSeparator:
        return "Invalid separator";
    case ScpiError::DataTypeError:
        return "Data type error";
    case ScpiError::ParameterNotAllowed:
        return "Parameter not allowed";
    case ScpiError::MissingParameter:
        return "Missing parameter";
    case ScpiError::UndefinedHeader:
        return "Undefined header";
    case ScpiError::InvalidStringData:
        return "Invalid string data";
    case ScpiError::QueueOverflow:
        return "Queue overflow";
    case ScpiError::InputBufferOverrun:
        return "Input buffer overrun";
    }
    return "Unknown error";
}

std::vector<Command> parse_message(std::string_view message)
{
    std::vector<Command> out;
    std::size_t start = 0;
    bool quoted = false;
    for (std::size_t i = 0; i <= message.size(); ++i) {
        if (i < message.size()) {
            if (message[i] == '"')
                quoted = !quoted;   // a ';' inside a string is the string's ("" toggles twice)
            if (quoted || message[i] != ';')
                continue;
        }
        // One command: message[start, i), trimmed of spaces.
        std::size_t a = start;
        std::size_t b = i;
        while (a < b && is_space(message[a]))
            ++a;
        while (b > a && is_space(message[b - 1]))
            --b;
        start = i + 1;
        if (a == b)
            continue;   // an empty command
        if (out.size() == kMaxCommandsPerMessage) {
            Command rest;
            rest.error = ScpiError::InputBufferOverrun;
            rest.error_at = a;
            rest.text = message.substr(a);
            out.push_back(std::move(rest));
            break;
        }
        out.push_back(CommandReader(message.substr(a, b - a), a).read());
    }
    return out;
}

} // namespace rigsim::mcs2
