#include "emulator/core/json_text.hpp"

#include "emulator/core/config_reader.hpp"

#include <utility>
#include <vector>

namespace rigsim {
namespace {

using nlohmann::json;

/// Builds the value from nlohmann's SAX events (as its own DOM parser does, whose stack it
/// keeps private), checking depth and keys on the way. Each event costs O(1) but the key
/// lookup, so the parse is linear.
class Builder {
public:
    explicit Builder(const JsonTextLimits& limits) : limits_(limits) {}

    json take() { return std::move(root_); }

    bool null() { return put(json(nullptr)); }
    bool boolean(bool v) { return put(json(v)); }
    bool number_integer(json::number_integer_t v) { return put(json(v)); }
    bool number_unsigned(json::number_unsigned_t v) { return put(json(v)); }
    bool number_float(json::number_float_t v, const std::string&) { return put(json(v)); }
    bool string(std::string& v) { return put(json(std::move(v))); }
    bool binary(json::binary_t& v) { return put(json(std::move(v))); }

    bool start_object(std::size_t) { return open(json::object()); }
    bool start_array(std::size_t) { return open(json::array()); }
    bool end_object() { return close(); }
    bool end_array() { return close(); }

    bool key(std::string& k)
    {
        auto& top = stack_.back();
        if (limits_.unique_keys && top->contains(k))
            throw JsonTextError(JsonTextError::Kind::DuplicateKey, "duplicate key " + quote(k), byte_, pointer(false));
        key_ = std::move(k);
        return true;
    }

    bool parse_error(std::size_t byte, const std::string&, const nlohmann::detail::exception& e)
    {
        // 406: a number no double holds; everything else is a syntax error.
        const auto kind = e.id == 406 ? JsonTextError::Kind::NumberOverflow : JsonTextError::Kind::Syntax;
        throw JsonTextError(kind, e.what(), byte, kind == JsonTextError::Kind::Syntax ? std::string() : pointer(true));
    }

private:
    /// `value` into the innermost container, or as the root; the new value's address.
    json* place(json&& value)
    {
        if (stack_.empty()) {
            root_ = std::move(value);
            return &root_;
        }
        auto& top = *stack_.back();
        if (top.is_array()) {
            top.push_back(std::move(value));
            return &top.back();
        }
        auto& slot = top[key_];
        slot = std::move(value);
        return &slot;
    }

    bool put(json&& value)
    {
        place(std::move(value));
        return true;
    }

    bool open(json&& container)
    {
        if (stack_.size() >= limits_.max_depth)
            throw JsonTextError(JsonTextError::Kind::TooDeep,
                                "nested deeper than " + std::to_string(limits_.max_depth) + " levels", byte_,
                                pointer(true));
        stack_.push_back(place(std::move(container)));
        keys_.push_back(key_);
        return true;
    }

    bool close()
    {
        stack_.pop_back();
        key_ = std::move(keys_.back());
        keys_.pop_back();
        return true;
    }

    /// The pointer of the innermost open container, and with `with_slot` of the slot a value
    /// goes to next in it (its pending key, or its next index). Built only for an error.
    std::string pointer(bool with_slot) const
    {
        std::string p;
        for (std::size_t i = 0; i < stack_.size(); ++i) {
            const bool last = i + 1 == stack_.size();
            if (last && !with_slot)
                break;
            // The slot of container i: the key it was being filled under (kept in keys_[i+1]
            // for an object once a child opened, key_ for the innermost), or its size.
            const auto& slot_key = last ? key_ : keys_[i + 1];
            p = stack_[i]->is_object() ? pointer_to(p, slot_key)
                                       : pointer_to(p, stack_[i]->size() - (last ? 0 : 1));
        }
        return p;
    }

    const JsonTextLimits& limits_;
    json root_;
    std::vector<json*> stack_;        ///< open containers, outermost first
    std::vector<std::string> keys_;   ///< keys_[i]: the pending key of container i-1 when container i opened
    std::string key_;                 ///< the pending key of the innermost object
    std::size_t byte_ = 0;            ///< not tracked by SAX events: 0 for checks other than syntax
};

} // namespace

json parse_json_text(std::string_view text, const JsonTextLimits& limits)
{
    Builder builder(limits);
    json::sax_parse(text.begin(), text.end(), &builder, json::input_format_t::json, true);
    return builder.take();
}

} // namespace rigsim
