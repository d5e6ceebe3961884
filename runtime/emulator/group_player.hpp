// Plays a stored action group in emulated time: each action moves its servos to their targets
// over the action's time, scaled by the group's speed percentage (200 = twice as fast). A run
// of `times` loops ends with a GroupFinished notification at the moment the last action ends;
// times = 0 loops until stopped (no GroupFinished). Action times are the controller's own
// milliseconds: on a clock `clock_ppm` fast they last that much less host time
// (board_clock.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "protocol/lsc/group_download.hpp"
#include "protocol/lsc/lsc_messages.hpp"
#include "runtime/emulator/servo_model.hpp"
#include "runtime/io/clock.hpp"

namespace seqc::emu {

struct Notification {
  io::TimePoint at;
  lsc::Reply message;
};

class GroupPlayer {
 public:
  explicit GroupPlayer(std::int32_t clock_ppm = 0) : clock_ppm_(clock_ppm) {}

  // Starts playing `actions` (non-empty) at `at`, replacing whatever was playing.
  void start(std::uint8_t group, std::uint16_t times, std::vector<lsc::GroupAction> actions,
             std::uint16_t percent, io::TimePoint at);
  void stop();
  // Changes the speed from `at` on: the rest of the current action is rescaled.
  void set_speed(std::uint16_t percent, io::TimePoint at, ServoBank& servos);

  // Runs playback up to `t`: moves servos for every action that starts at or before `t`,
  // and returns the notifications due by then, with their times.
  std::vector<Notification> advance_to(io::TimePoint t, ServoBank& servos);
  // When the next notification is due (nullopt if none will come without new commands).
  std::optional<io::TimePoint> next_notification_at() const;

  std::optional<std::uint8_t> group() const;
  // Whole loops completed so far in the current run.
  std::size_t loops_done() const;

 private:
  // Action time at the current speed; never below 1 ms so a group of zero-time actions
  // looping forever cannot stall emulated time.
  io::Duration scaled(std::uint16_t ms) const;
  void issue(io::TimePoint from, io::Duration duration, ServoBank& servos) const;

  struct State {
    std::uint8_t group = 0;
    std::uint16_t times = 0;
    std::vector<lsc::GroupAction> actions;
    std::uint16_t percent = 100;
    std::size_t loops = 0;
    std::size_t index = 0;
    io::TimePoint action_start{0};
    io::TimePoint action_end{0};
    bool issued = false;
  };
  std::int32_t clock_ppm_ = 0;
  std::optional<State> s_;
};

}  // namespace seqc::emu
