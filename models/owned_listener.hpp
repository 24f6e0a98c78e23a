#pragma once
// The listener a body tells of its events (a flip mount's arrival, a paddle's end of move), set by
// the module that owns it. A power cycle builds the device's new module, which takes the listener
// over, before the old one goes: the old one's clear() must not remove the new one's, so each is
// set and cleared under its owner.

#include <functional>
#include <utility>

namespace rigsim::models {

template <class... Args> class OwnedListener {
public:
    using Fn = std::function<void(Args...)>;

    /// `fn` is `owner`'s listener from now on.
    void set(const void* owner, Fn fn)
    {
        owner_ = owner;
        fn_ = std::move(fn);
    }
    /// No listener any more, if `owner`'s is the one set.
    void clear(const void* owner)
    {
        if (owner_ == owner) {
            owner_ = nullptr;
            fn_ = nullptr;
        }
    }
    /// Tell the listener, if there is one.
    void operator()(Args... args) const
    {
        if (fn_)
            fn_(args...);
    }

private:
    const void* owner_ = nullptr;
    Fn fn_;
};

} // namespace rigsim::models
