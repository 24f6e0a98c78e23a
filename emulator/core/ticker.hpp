#pragma once
// The one Asio timer that paces the Clock against wall time (simavr's avr->sleep hook:
// the daemon sleeps, tests bypass it and step the clock).
//
// Drift-free: the wall time of tick k is start + k / (tick_hz * time_scale); the clock is
// brought to the tick that is due now (never by counting timer firings). While nothing
// moves, the timer is not armed at all, so an idle rig costs no CPU; I/O calls sync()
// before it hands bytes to a device, so a command always sees the current tick.

#include "models/clock.hpp"

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

#include <chrono>

namespace rigsim {

class Ticker {
public:
    /// `min_period` bounds the wake-up rate when the clock is scaled beyond 1 tick per period.
    Ticker(boost::asio::io_context& io, Clock& clock, double time_scale,
           std::chrono::steady_clock::duration min_period = std::chrono::milliseconds(1));

    /// Advance the clock to the tick that is due at the current wall time.
    void sync();
    /// Arm the timer for the clock's next wake-up (call after anything that may start motion).
    void reschedule();
    void stop();

    double time_scale() const { return time_scale_; }

private:
    using SteadyClock = std::chrono::steady_clock;
    SteadyClock::time_point wall_of(Ticks t) const;
    Ticks due_at(SteadyClock::time_point wall) const;
    void on_timer(const boost::system::error_code& ec);

    Clock& clock_;
    double time_scale_;
    SteadyClock::duration min_period_;
    SteadyClock::time_point start_;
    boost::asio::steady_timer timer_;
    SteadyClock::time_point armed_for_ = SteadyClock::time_point::max();
    SteadyClock::time_point last_fire_;
    bool stopped_ = false;
};

} // namespace rigsim
