#include "emulator/apt/flipper_module.hpp"
#include "emulator/core/log_format.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

namespace rigsim::apt {

namespace {

constexpr std::uint32_t kAtPosition1 = 0x00000001;
constexpr std::uint32_t kAtPosition2 = 0x00000002;
constexpr std::uint32_t kMovingTo1 = 0x00000010;
constexpr std::uint32_t kMovingTo2 = 0x00000020;

} // namespace

FlipperModule::FlipperModule(const UnitIdentity& unit, std::size_t bay, std::uint8_t address, models::Flipper& arm,
                             int power_up_position, const Clock& clock, spdlog::logger& log, SaveToEeprom save)
    : Module(unit, bay, address, log, std::move(save)), arm_(arm), power_up_position_(power_up_position),
      clock_(clock)
{
    arm_.set_listener(this, [this](Ticks, int position) { arrived(position); });
}

FlipperModule::~FlipperModule()
{
    arm_.clear_listener(this);   // the world outlives its devices
}

void FlipperModule::handle(const msg::Message& m, Request& r)
{
    visit_as(*this, m, r);
}

Ticks FlipperModule::next_change(Ticks now) const
{
    // An arrival the world has woken the arm for is reported at that tick (the world ticks first).
    if (!arrivals_.empty())
        return now + 1;
    const Ticks at = arm_.next_event(now);
    return at == kNever ? kNever : std::max(at, now + 1);
}

void FlipperModule::tick(Ticks now)
{
    arm_.on_event(now);   // the world has woken it already; a late tick catches up
}

std::vector<std::string> FlipperModule::take_unprompted(std::uint8_t host)
{
    std::vector<std::string> frames;
    for (const int position : arrivals_) {
        const std::uint32_t bits = position == 2 ? kAtPosition2 : kAtPosition1;
        frames.push_back(msg::encode(msg::MoveCompleted{msg::MotStatus{kChan1, 0, 0, bits}}, host, address_));
    }
    arrivals_.clear();
    return frames;
}

void FlipperModule::power_down(bool restore_positions)
{
    // The arm stays where it is (or was going: it finishes its flip on the spring of its
    // mechanism); with the mechanics restored, where the rig put it.
    arm_.place(restore_positions ? power_up_position_ : arm_.target());
    arrivals_.clear();
}

void FlipperModule::arrived(int position)
{
    arrivals_.push_back(position);
    publish("flipper", {{"position", position}});
}

std::uint32_t FlipperModule::status_bits() const
{
    const auto now = clock_.now();
    switch (arm_.position_at(now)) {
    case 1:
        return kAtPosition1;
    case 2:
        return kAtPosition2;
    default:
        return arm_.target() == 1 ? kMovingTo1 : kMovingTo2;
    }
}

void FlipperModule::on(const msg::MoveJog& m)
{
    if (m.direction != 1 && m.direction != 2)
        return ignore(fmt::format("{}: MOT_MOVE_JOG direction {} (a flipper's position: 1 or 2): ignored",
                                  request_->peer, m.direction));
    const auto now = clock_.now();
    if (arm_.position_at(now) == m.direction) {
        // Already there: the move is done at once (nothing turns).
        arrivals_.push_back(m.direction);
        return;
    }
    const auto ticks = std::llround(static_cast<double>(params_.transit_time) * clock_.tick_hz() / 1000.0);
    arm_.move_to(now, m.direction, std::max<Ticks>(1, ticks));
}

void FlipperModule::on(const msg::ReqStatusBits&)
{
    answer(msg::GetStatusBits{kChan1, status_bits()});
}

void FlipperModule::on(const msg::SetEepromParams& m)
{
    save_to_eeprom_(m.msg_id, request_->peer);
}

void FlipperModule::on(const msg::SetMffOperParams& m)
{
    // The ranges (issue 37 p. 183-184) were checked before; the transit applies from the next flip.
    params_ = m.params;
    params_.chan_ident = kChan1;
}

void FlipperModule::on(const msg::ReqMffOperParams&)
{
    answer(msg::GetMffOperParams{params_});
}

void FlipperModule::describe(nlohmann::json& out) const
{
    const auto now = clock_.now();
    out["position"] = arm_.position_at(now);   // 0 while the arm travels
    out["target"] = arm_.target();
    out["moving"] = arm_.moving_at(now);
    out["transit_time_ms"] = params_.transit_time;
    out["dig_io"] = nlohmann::json::array(
        {{{"oper_mode", params_.dig_io1_oper_mode}, {"sig_mode", params_.dig_io1_sig_mode},
          {"pulse_width_ms", params_.dig_io1_pulse_width}},
         {{"oper_mode", params_.dig_io2_oper_mode}, {"sig_mode", params_.dig_io2_sig_mode},
          {"pulse_width_ms", params_.dig_io2_pulse_width}}});
    out["status"] = status_bits();
}

} // namespace rigsim::apt
