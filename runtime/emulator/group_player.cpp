#include "runtime/emulator/group_player.hpp"

#include <algorithm>

#include "runtime/emulator/board_clock.hpp"

namespace seqc::emu {

io::Duration GroupPlayer::scaled(std::uint16_t ms) const {
  const std::int64_t pct = s_ && s_->percent > 0 ? s_->percent : 100;
  const std::int64_t ns = static_cast<std::int64_t>(ms) * 1000000 * 100 / pct;
  return std::max(board_to_host(io::Duration{ns}, clock_ppm_),
                  io::Duration{std::chrono::milliseconds(1)});
}

void GroupPlayer::start(std::uint8_t group, std::uint16_t times,
                        std::vector<lsc::GroupAction> actions, std::uint16_t percent,
                        io::TimePoint at) {
  if (actions.empty()) {
    s_.reset();
    return;
  }
  s_ = State{};
  s_->group = group;
  s_->times = times;
  s_->actions = std::move(actions);
  s_->percent = percent;
  s_->action_start = at;
  s_->action_end = at + scaled(s_->actions[0].time_ms);
}

void GroupPlayer::stop() { s_.reset(); }

void GroupPlayer::issue(io::TimePoint from, io::Duration duration, ServoBank& servos) const {
  for (const auto& target : s_->actions[s_->index].servos) {
    servos.move(target.id, target.position, duration, from);
  }
}

void GroupPlayer::set_speed(std::uint16_t percent, io::TimePoint at, ServoBank& servos) {
  if (!s_ || percent == 0) return;
  const std::uint16_t old = s_->percent;
  s_->percent = percent;
  if (s_->issued && at < s_->action_end) {
    const auto remaining = (s_->action_end - at).count();
    s_->action_end = at + io::Duration{remaining * old / percent};
    issue(at, s_->action_end - at, servos);
  } else if (!s_->issued) {
    s_->action_end = s_->action_start + scaled(s_->actions[s_->index].time_ms);
  }
}

std::vector<Notification> GroupPlayer::advance_to(io::TimePoint t, ServoBank& servos) {
  std::vector<Notification> out;
  while (s_) {
    if (!s_->issued) {
      if (s_->action_start > t) break;
      issue(s_->action_start, s_->action_end - s_->action_start, servos);
      s_->issued = true;
    }
    if (s_->action_end > t) break;
    if (++s_->index == s_->actions.size()) {
      s_->index = 0;
      ++s_->loops;
      if (s_->times != 0 && s_->loops == s_->times) {
        out.push_back({s_->action_end, lsc::GroupFinished{s_->group, s_->times}});
        s_.reset();
        break;
      }
    }
    s_->action_start = s_->action_end;
    s_->action_end = s_->action_start + scaled(s_->actions[s_->index].time_ms);
    s_->issued = false;
  }
  return out;
}

std::optional<io::TimePoint> GroupPlayer::next_notification_at() const {
  if (!s_ || s_->times == 0) return std::nullopt;
  io::TimePoint end = s_->action_end;
  io::Duration loop{0};
  for (std::size_t i = 0; i < s_->actions.size(); ++i) {
    const io::Duration d = scaled(s_->actions[i].time_ms);
    loop += d;
    if (i > s_->index) end += d;
  }
  const auto loops_left =
      static_cast<std::int64_t>(s_->times) - static_cast<std::int64_t>(s_->loops) - 1;
  return end + loop * loops_left;
}

std::optional<std::uint8_t> GroupPlayer::group() const {
  if (!s_) return std::nullopt;
  return s_->group;
}

std::size_t GroupPlayer::loops_done() const { return s_ ? s_->loops : 0; }

}  // namespace seqc::emu
